// The renders measured as photographs are (issues 46 and 47): sward-render's previews at 640x480, read by
// `sward-eval look` as a user would run it.
// - Issue 46: bare soil of examples/tracks seen from the ground (1 and 1.6 m up) and from 8 m straight above has the
//   grain, colour and keypoints of real soil (the thresholds, below the real photographs' medians), and the
//   turf between the plants of the default meadow and the rover's track is not smooth felt: it passes the
//   sharp-texture test and has corners of its own.
// - Issue 47: the vegetation of those two ground views (4x MSAA) has the colour, contrast, scale and keypoint
//   statistics of real meadows, and its band at the horizon is soft and desaturated.
#include "gpu_test.h"

#include "scene/scene.h"
#include "scene/terrain.h"
#include "test_files.h"

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

using namespace sward;
using sward::test::GpuTest;
using sward::test::tempDir;

namespace {

// Renders frame 0 of `scene` at 640x480 (with `args`) and returns look.json of sward-eval look on it.
nlohmann::json renderAndLook(const std::string& scene, const std::string& args, const std::string& name) {
    const std::string out = tempDir("ground-look-" + name);
    const std::string render = SWARD_RENDER_EXE " " + scene + " --frames 0:1 --resolution 640x480 -q " + args +
                               " --out " + out + " >/dev/null 2>&1";
    EXPECT_EQ(std::system(render.c_str()), 0) << render;
    const std::string look = SWARD_EVAL_EXE " look " + out + " --no-pictures --out " + out + "/look >/dev/null 2>&1";
    EXPECT_EQ(std::system(look.c_str()), 0) << look;
    return nlohmann::json::parse(test::readText(out + "/look/look.json"));
}

// The same, once per test binary for each name: the ground views of the example scenes serve several tests.
const nlohmann::json& lookOf(const std::string& scene, const std::string& args, const std::string& name) {
    static std::map<std::string, nlohmann::json> cache;
    auto found = cache.find(name);
    if (found == cache.end()) found = cache.emplace(name, renderAndLook(scene, args, name)).first;
    return found->second;
}

// The ground view of examples/<name>.json, frame 0, 4x MSAA (the issues' views).
const nlohmann::json& exampleLook(const std::string& name) {
    return lookOf(SWARD_SOURCE_DIR "/examples/" + name + ".json", "--samples 4", name);
}

double figure(const nlohmann::json& region, const char* key) {
    const nlohmann::json& value = region.at(key);
    return value.is_number() ? value.get<double>() : -1e9; // null: no window / no eroded pixel fits
}

} // namespace

TEST_F(GpuTest, BareSoilOfTheTracksSceneMeasuresLikeSoilFromTheGroundAndFromAbove) {
    const std::string scene = SWARD_EXAMPLES_DIR "/tracks/tracks.json";
    const Ground ground = buildTerrain(loadScene(scene));
    // The scene's bare soil lies east of x = 42 m.
    const auto z = [&](double x, double y) { return ground.height(glm::vec2(float(x), float(y))); };
    const struct {
        const char* name;
        glm::dvec3 eye, target;
    } views[] = {{"ground-1m", {58.0, 20.0, z(58.0, 20.0) + 1.0}, {58.0, 22.0, z(58.0, 22.0)}},
                 {"ground-1.6m", {58.0, 20.0, z(58.0, 20.0) + 1.6}, {58.0, 27.0, z(58.0, 27.0)}},
                 {"top-down-8m", {58.0, 40.0, z(58.0, 40.0) + 8.0}, {58.0, 40.01, z(58.0, 40.0)}}};
    for (const auto& view : views) {
        char args[160];
        std::snprintf(args, sizeof args, "--camera %.3f,%.3f,%.3f --look-at %.3f,%.3f,%.3f", view.eye.x, view.eye.y,
                      view.eye.z, view.target.x, view.target.y, view.target.z);
        const nlohmann::json soil = lookOf(scene, args, view.name).at("summary").at("soil");
        std::printf("%s: %s\n", view.name, soil.dump().c_str());
        EXPECT_GT(figure(soil, "pixels"), 50000.0) << view.name;
        EXPECT_GE(figure(soil, "gradient_mean"), 0.012) << view.name;
        EXPECT_GE(figure(soil, "fast_per_mp"), 3000.0) << view.name;
        EXPECT_GE(figure(soil, "orb_per_mp"), 5000.0) << view.name;
        EXPECT_LE(figure(soil, "saturation_mean"), 0.20) << view.name;
        EXPECT_GE(figure(soil, "hue_std_deg"), 10.0) << view.name;
        EXPECT_GE(figure(soil, "laplacian_rms_0"), 0.02) << view.name;
        EXPECT_GE(figure(soil, "spectrum_slope_high"), -3.5) << view.name;
        EXPECT_LE(figure(soil, "spectrum_slope_high"), -1.0) << view.name;
        EXPECT_GE(figure(soil, "grey_std"), 0.003) << view.name;
    }
}

TEST_F(GpuTest, TurfBetweenThePlantsIsNotSmoothInGroundViewsOfTheMeadowAndTheRoverTrack) {
    for (const char* name : {"meadow", "rover-track"}) {
        const nlohmann::json& look = exampleLook(name);
        const double smooth = look.at("smooth_turf_share").get<double>();
        std::printf("%s: smooth turf %.4f of the non-sky pixels, turf %s\n", name, smooth,
                    look.at("summary").at("turf").dump().c_str());
        EXPECT_GT(figure(look.at("summary").at("turf"), "pixels"), 5000.0) << name << ": no turf in view";
        EXPECT_LE(smooth, 0.05) << name;
        // Grain of its own: corners inside the turf, away from the plants' edges (the smooth olive turf before
        // issue 46 had 830 and 2,400 FAST keypoints per megapixel in these two views, the real meadows 14,000).
        EXPECT_GE(figure(look.at("summary").at("turf"), "fast_per_mp"), 5000.0) << name;
    }
}

TEST_F(GpuTest, VegetationOfTheMeadowAndTheRoverTrackMeasuresLikeARealMeadow) {
    // Issue 47's bounds (before it: saturation 0.70-0.74, value std 0.15-0.17, gradient mean 0.06, Laplacian 0.18 and
    // 0.10-0.12, 46,000-49,000 FAST per megapixel, 99 % sharp texture; far band 82-99.7 % sharp, saturation 0.67-0.73;
    // the real meadows 0.16, 0.109, 0.032, 0.096 and 0.057, 14,000, 71 %; far band 68 %, 0.13). The high band of the
    // spectrum stays within the real range, so the way there is not a blur. The rover view, dense grass from 1 m, is
    // held instead to the real photograph of that view (docs/evaluation.md, "After issue 47"): BotanicGarden's tall
    // grass from a ground robot measures d/dx kurtosis 1.92 and sharp fraction 0.945 (the rover view 2.17 and 0.961;
    // with 32 thin near blades 1.26 and 0.985, every edge crisp).
    for (const std::string name : {"meadow", "rover-track"}) {
        const nlohmann::json& vegetation = exampleLook(name).at("summary").at("vegetation");
        const nlohmann::json& far = exampleLook(name).at("summary").at("far");
        std::printf("%s: vegetation %s\nfar %s\n", name.c_str(), vegetation.dump().c_str(), far.dump().c_str());
        EXPECT_GT(figure(vegetation, "pixels"), 50000.0) << name;
        EXPECT_GE(figure(vegetation, "saturation_mean"), 0.12) << name;
        EXPECT_LE(figure(vegetation, "saturation_mean"), 0.40) << name;
        EXPECT_LE(figure(vegetation, "value_std"), 0.14) << name;
        EXPECT_LE(figure(vegetation, "gradient_mean"), 0.045) << name;
        EXPECT_LE(figure(vegetation, "laplacian_rms_0"), 0.14) << name;
        EXPECT_LE(figure(vegetation, "fast_per_mp"), 30000.0) << name;
        EXPECT_GE(figure(vegetation, "spectrum_slope_high"), -2.8) << name;
        EXPECT_LE(figure(vegetation, "spectrum_slope_high"), -1.7) << name;
        EXPECT_LE(figure(vegetation, "laplacian_rms_2"), 0.085) << name;
        const bool meadow = name == "meadow";
        EXPECT_GE(figure(vegetation, "dx_excess_kurtosis"), meadow ? 2.8 : 1.9) << name;
        EXPECT_LE(figure(vegetation, "sharp_fraction"), meadow ? 0.90 : 0.97) << name;
        EXPECT_GT(figure(far, "pixels"), 5000.0) << name;
        EXPECT_LE(figure(far, "sharp_fraction"), 0.90) << name;
        EXPECT_LE(figure(far, "saturation_mean"), 0.35) << name;
    }
}

// Issue 47: colour and labels agree at the horizon. Sky-labelled pixels 2-6 px above the horizon of the meadow's
// ground view (the topmost pixel in each column the semantic image does not label sky) carry no plant colour: their
// preview equals, within 8 of 255, the same render without plants (tools/horizon-colour.py measures the same).
// Far billboards once tinted 199 of those 3,200 pixels (alpha to coverage outside the truth's silhouette and a card's
// top edge reading the atlas cell above); before the far cover (db5c023^) 3 were.
TEST_F(GpuTest, FarPlantsLeaveTheSkyAboveTheHorizonOfTheMeadowUntinted) {
    // The renderer's own image: without the example's camera model, whose optics blur any colour into its neighbours.
    const std::filesystem::path out = test::tempDir();
    nlohmann::json meadow = nlohmann::json::parse(test::readText(SWARD_SOURCE_DIR "/examples/meadow.json"));
    meadow["camera"].erase("sensor");
    const std::string scene = (out / "meadow.json").string();
    std::ofstream(scene) << meadow.dump();
    for (const char* variant : {"plants", "bare"}) {
        const std::string render =
            SWARD_RENDER_EXE " " + scene + " --frames 0:1 --resolution 640x480 --samples 4 -q --out " +
            (out / variant).string() + (std::string(variant) == "bare" ? " --no-vegetation" : "") + " >/dev/null 2>&1";
        ASSERT_EQ(std::system(render.c_str()), 0) << render;
    }
    const cv::Mat semantic = cv::imread((out / "plants/semantic/000000.png").string(), cv::IMREAD_UNCHANGED);
    const cv::Mat plants = cv::imread((out / "plants/preview/000000.png").string(), cv::IMREAD_COLOR);
    const cv::Mat bare = cv::imread((out / "bare/preview/000000.png").string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(semantic.empty() || plants.empty() || bare.empty());
    ASSERT_EQ(semantic.type(), CV_8UC1);
    uint32_t examined = 0, tinted = 0;
    for (int x = 0; x < semantic.cols; ++x) {
        int horizon = 0;
        while (horizon < semantic.rows && semantic.at<uint8_t>(horizon, x) == 0) ++horizon;
        if (horizon == semantic.rows) continue;
        for (int y = std::max(horizon - 6, 0); y <= horizon - 2; ++y) {
            if (semantic.at<uint8_t>(y, x) != 0) continue;
            ++examined;
            const cv::Vec3b a = plants.at<cv::Vec3b>(y, x), b = bare.at<cv::Vec3b>(y, x);
            int difference = 0;
            for (int k = 0; k < 3; ++k) difference = std::max(difference, std::abs(int(a[k]) - int(b[k])));
            tinted += difference > 8;
        }
    }
    std::printf("%u of %u sky-labelled pixels 2-6 px above the horizon differ by more than 8 of 255\n", tinted,
                examined);
    ASSERT_GT(examined, 1000u) << "the view shows too little horizon to measure";
    EXPECT_LE(tinted, 3u);
}

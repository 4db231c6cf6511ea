// sward-render datasets read back as a user's tools read them (OpenCV, a PFM reader of our own, the JSON files):
// ground-truth consistency, shards, resume after a kill, identical manifests, bare-ground runs, rover tracks.
#include "gpu_test.h"
#include "pfm_reader.h"

#include "shared/gpu_layout.h"

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <sys/wait.h>

using sward::test::readPfm;
using sward::test::tempDir;

namespace {

const std::string kScene = SWARD_TEST_DATA_DIR "/dataset_scene.json";

struct RunResult {
    int exitCode = -1;
    std::string out, err;
};

std::string readFile(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

RunResult render(const std::string& args, const std::string& prefix = "") {
    std::string dir = tempDir("dataset-log");
    std::string command = prefix + " " SWARD_RENDER_EXE " " + args + " --validation >" + dir + "/out.txt 2>" + dir + "/err.txt";
    int status = std::system(command.c_str());
    int code = WIFEXITED(status) ? WEXITSTATUS(status) : WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1;
    return {code, readFile(dir + "/out.txt"), readFile(dir + "/err.txt")};
}

nlohmann::json readJson(const std::string& path) { return nlohmann::json::parse(readFile(path)); }

// Middlebury calib.txt as key -> value text.
std::map<std::string, std::string> readCalib(const std::string& path) {
    std::map<std::string, std::string> values;
    std::istringstream lines(readFile(path));
    for (std::string line; std::getline(lines, line);)
        if (auto eq = line.find('='); eq != std::string::npos) values[line.substr(0, eq)] = line.substr(eq + 1);
    return values;
}

cv::Mat readImage(const std::string& path) {
    cv::Mat image = cv::imread(path, cv::IMREAD_UNCHANGED);
    EXPECT_FALSE(image.empty()) << "cannot read " << path;
    return image;
}

std::vector<std::string> manifestFiles(const nlohmann::json& manifest) {
    std::vector<std::string> files;
    for (auto it = manifest.at("files").begin(); it != manifest.at("files").end(); ++it) files.push_back(it.key());
    return files;
}

// One full reference run of the test scene, shared by the tests that compare against it.
const std::string& referenceRun() {
    static const std::string dir = [] {
        std::string out = tempDir("dataset-reference");
        RunResult r = render(kScene + " --out " + out);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return out;
    }();
    return dir;
}

} // namespace

TEST(Dataset, DisparityPfmKittiAndCalibAgreeWithDepthEverywhere) {
    const std::string& dir = referenceRun();
    auto calib = readCalib(dir + "/calib.txt");
    double f = 0, cx = 0, cy = 0;
    ASSERT_EQ(std::sscanf(calib.at("cam0").c_str(), "[%lf 0 %lf; 0 %*f %lf", &f, &cx, &cy), 3) << calib.at("cam0");
    const double baselineMm = std::stod(calib.at("baseline")), doffs = std::stod(calib.at("doffs"));
    EXPECT_EQ(std::stoi(calib.at("width")), 160);
    EXPECT_EQ(std::stoi(calib.at("height")), 120);

    for (const char* frame : {"000000", "000005"}) {
        cv::Mat depth = readImage(dir + "/depth/" + frame + ".exr");
        cv::Mat disparity = readImage(dir + "/disparity/" + frame + ".exr");
        cv::Mat kitti = readImage(dir + "/disparity/" + frame + ".png");
        cv::Mat pfm = readPfm(dir + "/disparity/" + frame + ".pfm");
        ASSERT_EQ(depth.type(), CV_32F);
        ASSERT_EQ(disparity.type(), CV_32F);
        ASSERT_EQ(kitti.type(), CV_16U);
        int valid = 0, sky = 0;
        for (int y = 0; y < depth.rows; ++y)
            for (int x = 0; x < depth.cols; ++x) {
                const float z = depth.at<float>(y, x), d = disparity.at<float>(y, x);
                if (std::isinf(z)) { // sky: 0 in the EXR and KITTI, +inf in the PFM (Middlebury convention)
                    ++sky;
                    ASSERT_EQ(d, 0.0f);
                    ASSERT_EQ(kitti.at<uint16_t>(y, x), 0);
                    ASSERT_TRUE(std::isinf(pfm.at<float>(y, x)));
                    continue;
                }
                ++valid;
                ASSERT_GT(z, 0.0f);
                // disparity = f * B / Z, B in metres
                ASSERT_NEAR(d, f * baselineMm * 1e-3 / z, 1e-4 * d) << x << "," << y;
                // calib.txt reproduces the depth: Z[mm] = baseline * f / (d + doffs)
                ASSERT_NEAR(baselineMm * f / (d + doffs) * 1e-3, z, 1e-4 * z);
                ASSERT_EQ(pfm.at<float>(y, x), d);
                ASSERT_LE(std::abs(kitti.at<uint16_t>(y, x) / 256.0 - d), 0.5 / 256.0 + 1e-6);
            }
        EXPECT_GT(valid, 1000);
        EXPECT_GT(sky, 100);
    }
}

TEST(Dataset, SemanticAndInstanceMasksMatchTheDepth) {
    const std::string& dir = referenceRun();
    cv::Mat depth = readImage(dir + "/depth/000003.exr");
    cv::Mat semantic = readImage(dir + "/semantic/000003.png");
    cv::Mat instance = readImage(dir + "/instance/000003.exr");
    ASSERT_EQ(semantic.type(), CV_8U);
    ASSERT_EQ(instance.type(), CV_32F);
    std::map<int, int> classes;
    for (int y = 0; y < depth.rows; ++y)
        for (int x = 0; x < depth.cols; ++x) {
            int c = semantic.at<uint8_t>(y, x);
            float id = instance.at<float>(y, x);
            ++classes[c];
            ASSERT_EQ(c == sward::gpu::kSemanticSky, std::isinf(depth.at<float>(y, x))) << x << "," << y;
            const bool plant = (c >= 2 && c <= 5) || c == sward::gpu::kSemanticFelled || c == sward::gpu::kSemanticCut;
            ASSERT_EQ(plant, id > 0.0f) << "plants and only plants carry plant ids, at " << x << "," << y;
            ASSERT_EQ(id, std::floor(id));
        }
    // The meadow's ground under its plants is turf (a ground class, depth and no instance like bare ground).
    EXPECT_GT(classes[sward::gpu::kSemanticGround] + classes[sward::gpu::kSemanticTurf], 0);
    EXPECT_GT(classes[3], 1000) << "grass";
}

TEST(Dataset, RoverDrivingStraightLeavesFelledPlantsBehindIt) {
    const std::string& dir = referenceRun();
    auto calib = readCalib(dir + "/calib.txt");
    double f = 0, cx = 0, cy = 0;
    ASSERT_EQ(std::sscanf(calib.at("cam0").c_str(), "[%lf 0 %lf; 0 %*f %lf", &f, &cx, &cy), 3);
    std::vector<nlohmann::json> records;
    std::istringstream lines(readFile(dir + "/frames.jsonl"));
    for (std::string line; std::getline(lines, line);) records.push_back(nlohmann::json::parse(line));
    ASSERT_EQ(records.size(), 6u);

    int felledFirst = 0, felledLast = 0;
    for (int frame : {0, 5}) {
        char name[16];
        std::snprintf(name, sizeof name, "%06d", frame);
        cv::Mat semantic = readImage(dir + "/semantic/" + name + ".png");
        cv::Mat depth = readImage(dir + "/depth/" + name + ".exr");
        const nlohmann::json& pose = records[size_t(frame)].at("left_pose");
        // The rover drives from (50, 46) towards +y at 4 m/s (tests/gpu/data/dataset_scene.json).
        const double roverY = 46.0 + 4.0 * records[size_t(frame)].at("time").get<double>();
        int felled = 0;
        for (int y = 0; y < depth.rows; ++y)
            for (int x = 0; x < depth.cols; ++x) {
                if (semantic.at<uint8_t>(y, x) != sward::gpu::kSemanticFelled) continue;
                ++felled;
                const double z = depth.at<float>(y, x);
                const double c[3] = {(x - cx) / f * z, (y - cy) / f * z, z}; // OpenCV pixel centres
                double world[3];
                for (int r = 0; r < 3; ++r)
                    world[r] = pose[r][0].get<double>() * c[0] + pose[r][1].get<double>() * c[1] +
                               pose[r][2].get<double>() * c[2] + pose[r][3].get<double>();
                // On the rover's track (wheels 0.3 m either side of x = 50; flattened blades reach ~0.5 m) and
                // behind (or under) the front axle.
                EXPECT_NEAR(world[0], 50.0, 1.0) << "felled pixel off the track at " << x << "," << y;
                EXPECT_LT(world[1], roverY + 0.35 + 0.5) << "felled pixel ahead of the rover at " << x << "," << y;
            }
        (frame == 0 ? felledFirst : felledLast) = felled;
    }
    EXPECT_GT(felledLast, felledFirst + 20) << "the track grows as the rover drives on";
}

TEST(Dataset, ShardsTogetherEqualTheFullRunFileByFile) {
    const std::string& full = referenceRun();
    std::string sharded = tempDir("dataset-shards");
    for (const char* shard : {"0/2", "1/2"}) {
        RunResult r = render(kScene + " --out " + sharded + " --shard " + shard);
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    nlohmann::json manifest = readJson(full + "/manifest.json");
    nlohmann::json shard0 = readJson(sharded + "/manifest.shard-0-of-2.json");
    nlohmann::json shard1 = readJson(sharded + "/manifest.shard-1-of-2.json");
    EXPECT_EQ(shard0.at("frames"), nlohmann::json::array({0, 3}));
    EXPECT_EQ(shard1.at("frames"), nlohmann::json::array({3, 6}));
    std::vector<std::string> files = manifestFiles(manifest);
    EXPECT_GT(files.size(), 50u);
    for (const std::string& file : files) {
        const nlohmann::json& shardFiles = shard0.at("files").contains(file) ? shard0.at("files") : shard1.at("files");
        ASSERT_TRUE(shardFiles.contains(file)) << file << " is in no shard";
        EXPECT_EQ(shardFiles.at(file), manifest.at("files").at(file)) << file << " differs";
        EXPECT_EQ(readFile(full + "/" + file), readFile(sharded + "/" + file)) << file;
    }
}

TEST(Dataset, KilledRunResumesToIdenticalFilesAndManifest) {
    const std::string& full = referenceRun();
    std::string dir = tempDir("dataset-resume");
    // Kill the first run hard part-way (after some frames, or before any: both must resume correctly) and leave
    // a stale sward temporary behind as a crash mid-write on a file system without O_TMPFILE would (process
    // 999999999 does not exist). A user's own "*.tmp" file is not sward's to remove.
    RunResult killed = render(kScene + " --out " + dir, "timeout -s KILL 8");
    std::filesystem::create_directories(dir + "/left");
    std::ofstream(dir + "/left/.000004.exr.sward-999999999.tmp") << "half-written";
    std::ofstream(dir + "/left/000004.exr.tmp") << "the user's";
    RunResult resumed = render(kScene + " --out " + dir);
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/left/.000004.exr.sward-999999999.tmp"));
    EXPECT_EQ(readFile(dir + "/left/000004.exr.tmp"), "the user's");
    std::filesystem::remove(dir + "/left/000004.exr.tmp");
    EXPECT_EQ(readFile(full + "/manifest.json"), readFile(dir + "/manifest.json"))
        << "killed with exit " << killed.exitCode << ", then: " << resumed.out;
    // A third run has nothing left to do and changes nothing.
    RunResult again = render(kScene + " --out " + dir);
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_NE(again.out.find("0 rendered, 6 already complete"), std::string::npos) << again.out;
    EXPECT_EQ(readFile(full + "/manifest.json"), readFile(dir + "/manifest.json"));
}

TEST(Dataset, TwoRunsGiveIdenticalManifests) {
    const std::string& full = referenceRun();
    std::string dir = tempDir("dataset-again");
    ASSERT_EQ(render(kScene + " --out " + dir + " --frames 0:3").exitCode, 0);
    ASSERT_EQ(render(kScene + " --out " + dir + " --frames 3:6").exitCode, 0);
    ASSERT_EQ(render(kScene + " --out " + dir).exitCode, 0); // all complete: hashes only
    EXPECT_EQ(readFile(full + "/manifest.json"), readFile(dir + "/manifest.json"));
    nlohmann::json manifest = readJson(dir + "/manifest.json");
    for (const char* key : {"scene_sha256", "seed", "sward_revision", "device", "driver", "options"})
        EXPECT_TRUE(manifest.contains(key)) << key;
}

TEST(Dataset, IsSelfContainedWithSceneCopyClassesAssetsAndConventions) {
    const std::string& dir = referenceRun();
    EXPECT_EQ(readFile(dir + "/scene.json"), readFile(kScene)); // byte for byte
    const nlohmann::json classes = readJson(dir + "/classes.json");
    std::map<int, nlohmann::json> byId;
    for (const nlohmann::json& c : classes.at("classes")) byId[c.at("id").get<int>()] = c;
    EXPECT_EQ(byId.at(int(sward::gpu::kSemanticSky)).at("name"), "sky");
    EXPECT_EQ(byId.at(int(sward::gpu::kSemanticObject)).at("group"), "object");
    EXPECT_EQ(byId.at(int(sward::gpu::kSemanticVegetation) + 1).at("scene_name"), "grass"); // the scene's names
    EXPECT_FALSE(byId.at(int(sward::gpu::kSemanticVegetation) + 3).contains("scene_name")); // 3 categories
    for (const auto& [id, c] : byId) EXPECT_EQ(c.at("colour").size(), 3u) << id;

    const nlohmann::json manifest = readJson(dir + "/manifest.json");
    for (const char* file : {"scene.json", "classes.json", "frames.jsonl", "calib.txt"})
        EXPECT_TRUE(manifest.at("files").contains(file)) << file;
    EXPECT_EQ(manifest.at("units").at("depth"), "metre");
    EXPECT_NE(manifest.at("conventions").at("camera_axes").get<std::string>().find("OpenCV"), std::string::npos);
    EXPECT_TRUE(manifest.at("assets").is_object()); // the test scene reads no files: procedural everything
}

namespace {

// The occlusion rule written out independently of dataset/occlusion.cpp: `own` pixel x with disparity d shows its
// point at x + direction * d in `other`; it is hidden when that is outside the other image, or when every other
// centre around it (one when the match is on a centre) sees a surface nearer by more than 0.5 px.
bool seenByTheOtherView(const cv::Mat& own, const cv::Mat& other, int x, int y, int direction) {
    const double d = own.at<float>(y, x), match = x + direction * d;
    if (match < -0.5 || match > other.cols - 0.5) return false;
    const int before = int(std::floor(match));
    bool hidden = true;
    for (int centre : {before, before + 1}) {
        if (centre == before + 1 && match == before) break;
        const float o = other.at<float>(y, std::clamp(centre, 0, other.cols - 1));
        hidden = hidden && std::isfinite(o) && o > d + 0.5;
    }
    return !hidden;
}

// |other view's disparity interpolated at the match - d|: 0 up to float rounding when both centres around the
// match see the pixel's own planar surface; +inf when a centre has no truth or the match leaves the image.
double warpDifference(const cv::Mat& own, const cv::Mat& other, int x, int y, int direction) {
    const double d = own.at<float>(y, x), match = x + direction * d;
    if (match < 0.0 || match > other.cols - 1) return INFINITY;
    const int i = int(std::floor(match));
    const double t = match - i;
    const double a = other.at<float>(y, i), b = t > 0.0 ? other.at<float>(y, i + 1) : a;
    return std::abs((1.0 - t) * a + t * b - d);
}

// Whether the pixel and its row neighbours see one plane and the other view's disparity is one straight line over
// the centres match-1 .. match+2 (second differences below 1e-4 px): then, as far as the samples can tell, the two
// centres around the match see the pixel's own plane (not a blade too thin for the other view's centres to catch).
bool planarAroundMatch(const cv::Mat& own, const cv::Mat& other, int x, int y, int direction) {
    if (x < 1 || x + 1 >= own.cols) return false;
    const double left = own.at<float>(y, x - 1), centre = own.at<float>(y, x), right = own.at<float>(y, x + 1);
    if (!std::isfinite(left + centre + right) || std::abs(left - 2 * centre + right) >= 1e-4) return false;
    const double match = x + direction * centre;
    const int i = int(std::floor(match));
    if (i < 1 || i + 2 >= other.cols) return false;
    double v[4];
    for (int k = 0; k < 4; ++k) v[k] = other.at<float>(y, i - 1 + k);
    if (!std::isfinite(v[0] + v[1] + v[2] + v[3])) return false;
    return std::abs(v[0] - 2 * v[1] + v[2]) < 1e-4 && std::abs(v[1] - 2 * v[2] + v[3]) < 1e-4;
}

} // namespace

// Left-right consistency, both ways. A pixel's match in the other view falls between two pixel centres: where both
// see the pixel's own planar surface (the other view's disparity is linear there), the disparity interpolated at the
// match equals the pixel's within 1e-3 px — on every such pixel. Occluded pixels (the depth test: nearer surfaces at
// both centres by more than 0.5 px, or out of view) all fail that check; the pixels that fail it and are not
// occluded are those whose match falls between two different surfaces (a blade beside another), which no
// pixel-sampled truth can decide closer than the tolerance.
TEST(Dataset, RightViewTruthAndOcclusionMasksFollowTheDepthTestOfTheOtherView) {
    const std::string& dir = referenceRun();
    auto calib = readCalib(dir + "/calib.txt");
    const double f = std::stod(calib.at("cam0").substr(1)), baseline = std::stod(calib.at("baseline")) * 1e-3;
    for (const char* frame : {"000000", "000004"}) {
        const cv::Mat left = readPfm(dir + "/disparity/" + frame + ".pfm");
        const cv::Mat right = readPfm(dir + "/disparity_right/" + frame + ".pfm");
        const cv::Mat rightDepth = readImage(dir + "/depth_right/" + frame + ".exr");
        const cv::Mat masks[2] = {readImage(dir + "/occlusion/" + frame + ".png"),
                                  readImage(dir + "/occlusion_right/" + frame + ".png")};
        int occluded[2] = {0, 0}, visible[2] = {0, 0}, exact[2] = {0, 0}, close[2] = {0, 0}, planar[2] = {0, 0};
        for (int y = 0; y < left.rows; ++y)
            for (int x = 0; x < left.cols; ++x) {
                const float z = rightDepth.at<float>(y, x);
                if (std::isinf(z)) {
                    ASSERT_TRUE(std::isinf(right.at<float>(y, x)));
                } else {
                    ASSERT_NEAR(right.at<float>(y, x), f * baseline / z, 1e-5 * right.at<float>(y, x));
                }
                for (int view = 0; view < 2; ++view) {
                    const cv::Mat &own = view == 0 ? left : right, &other = view == 0 ? right : left;
                    const uint8_t m = masks[view].at<uint8_t>(y, x);
                    if (std::isinf(own.at<float>(y, x))) {
                        ASSERT_EQ(m, 0) << view << ": " << x << "," << y;
                        continue;
                    }
                    const bool seen = seenByTheOtherView(own, other, x, y, view == 0 ? -1 : +1);
                    ASSERT_EQ(m, seen ? 255 : 128) << view << ": " << x << "," << y;
                    (seen ? visible : occluded)[view] += 1;
                    const int direction = view == 0 ? -1 : +1;
                    const double difference = warpDifference(own, other, x, y, direction);
                    if (!seen) {
                        ASSERT_GT(difference, 1e-3) << "an occluded pixel passes: " << view << ": " << x << "," << y;
                    }
                    if (seen && planarAroundMatch(own, other, x, y, direction)) {
                        ASSERT_LE(difference, 1e-3) << "one plane, yet the warp disagrees: " << view << ": " << x << "," << y;
                        ++planar[view];
                    }
                    if (seen && difference <= 1e-3) ++exact[view];
                    if (seen && difference <= 0.1) ++close[view];
                }
            }
        for (int view = 0; view < 2; ++view) {
            std::printf("frame %s %s: %d visible (warp within 1e-3 px: %d, 0.1 px: %d; one plane around the match: "
                        "%d), %d occluded\n", frame, view ? "right" : "left", visible[view], exact[view], close[view],
                        planar[view], occluded[view]);
            EXPECT_GT(planar[view], visible[view] / 3) << "the exactness check must cover many pixels (41 % at 160x120)";
            EXPECT_GT(visible[view], 15 * occluded[view]) << "most pixels are seen by both cameras";
            EXPECT_GT(occluded[view], 10) << "at least the image border the other camera does not see";
            EXPECT_GT(close[view], 9 * visible[view] / 10) << "the other view's truth agrees where it is seen";
        }
    }
}

TEST(Dataset, ColourAlphaIsFullCoverageEverywhere) {
    const std::string& dir = referenceRun();
    for (const char* view : {"left", "right"}) {
        const cv::Mat colour = readImage(dir + "/" + view + "/000002.exr");
        ASSERT_EQ(colour.channels(), 4);
        std::vector<cv::Mat> channels;
        cv::split(colour, channels);
        EXPECT_EQ(cv::countNonZero(channels[3] != 1.0f), 0) << view;
    }
}

TEST(Dataset, NoVegetationHasNoVegetationPixels) {
    std::string dir = tempDir("dataset-bare");
    RunResult r = render(kScene + " --out " + dir + " --frames 0:1 --no-vegetation");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    cv::Mat semantic = readImage(dir + "/semantic/000000.png");
    cv::Mat instance = readImage(dir + "/instance/000000.exr");
    int ground = 0;
    for (int y = 0; y < semantic.rows; ++y)
        for (int x = 0; x < semantic.cols; ++x) {
            int c = semantic.at<uint8_t>(y, x);
            ASSERT_TRUE(c == sward::gpu::kSemanticSky || c == sward::gpu::kSemanticGround) << "class " << c;
            ASSERT_EQ(instance.at<float>(y, x), 0.0f);
            ground += c == sward::gpu::kSemanticGround;
        }
    EXPECT_GT(ground, 1000);
}

TEST(Dataset, MalformedSceneNamesTheJsonPathAndWritesNothing) {
    std::string dir = tempDir("dataset-bad");
    std::string scenePath = dir + "/bad.json";
    nlohmann::json scene = readJson(kScene);
    scene["camera"]["baseline"] = -1;
    std::ofstream(scenePath) << scene.dump();
    RunResult r = render(scenePath + " --out " + dir + "/out");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("camera.baseline"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
    r = render(kScene + " --out " + dir + "/out --shard 2/2");
    EXPECT_EQ(r.exitCode, 2) << "a bad option value is a usage error (tools/tool_main.h)";
    EXPECT_NE(r.err.find("shard"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
}

TEST(Dataset, SensorModelChangesColourOnlyAndIsRecordedInFramesJsonl) {
    std::string dir = tempDir("dataset-sensor");
    nlohmann::json scene = readJson(kScene);
    scene["camera"]["sensor"] = {{"k1", -0.05}, {"vignetting", 0.5}, {"electrons_per_unit", 2000}, {"read_noise", 3}};
    std::ofstream(dir + "/sensor.json") << scene.dump();
    RunResult r = render(dir + "/sensor.json --out " + dir + "/out --frames 0:1");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string& ideal = referenceRun();
    for (const char* file : {"/depth/000000.exr", "/disparity/000000.pfm", "/semantic/000000.png", "/instance/000000.exr"})
        EXPECT_EQ(readFile(ideal + file), readFile(dir + "/out" + file)) << file << ": ground truth stays ideal";
    for (const char* file : {"/left/000000.exr", "/right/000000.exr"})
        EXPECT_NE(readFile(ideal + file), readFile(dir + "/out" + file)) << file;
    nlohmann::json first = nlohmann::json::parse(readFile(dir + "/out/frames.jsonl").substr(0, readFile(dir + "/out/frames.jsonl").find('\n')));
    EXPECT_DOUBLE_EQ(first.at("sensor").at("k1").get<double>(), -0.05);
}

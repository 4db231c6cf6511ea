// sward-bench suite (render/bench_suite.h): the figures' plan in both modes, the run, and the output folder.
#include "render/bench_suite.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/optional_components.h"
#include "common/staged_folder.h"
#include "common/stopwatch.h"
#include "engine/device.h"
#include "range/range_benchmark.h"
#include "render/benchmarks.h"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <functional>
#include <optional>
#include <thread>

#ifndef SWARD_REVISION
#define SWARD_REVISION "unknown"
#endif

namespace sward {

namespace {

namespace fs = std::filesystem;

// One figure of the suite: what it measures and how, given the mode. `run` fills parameters (every setting that
// shapes the numbers, so quick and full figures are never confused) and returns the benchmark's own JSON;
// `summary` picks the headline numbers of that JSON for suite.md.
struct Figure {
    const char* name;
    const char* description;
    std::function<nlohmann::json(const SuiteOptions&, const std::string& root, nlohmann::json& parameters)> run;
    std::function<nlohmann::json(const nlohmann::json& result)> summary;
    std::optional<Component> needs = std::nullopt; // a component a lean build may leave out: skipped without it
};

std::string sizeText(uint32_t width, uint32_t height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

// The frame figures: the scene at a size, every pass timed, the plant draws counted (lanes per covered pixel).
nlohmann::json runFrame(const std::string& scenePath, uint32_t width, uint32_t height, uint32_t samples,
                        uint32_t frames, const SuiteOptions& options, nlohmann::json& parameters) {
    FrameBenchOptions frame{.scenePath = scenePath,
                            .width = width,
                            .height = height,
                            .samples = samples,
                            .frames = frames,
                            .device = options.device,
                            .cutoutCorners = {},
                            .floor = false};
    parameters = {{"scene", fs::path(scenePath).filename().string()},
                  {"resolution", sizeText(width, height)},
                  {"samples", samples},
                  {"frames", frames}};
    return benchFrame(frame);
}

nlohmann::json frameSummary(const nlohmann::json& r) {
    const nlohmann::json& pass = r.at("pass_ms");
    return {{"whole_frame_ms", r.at("whole_frame_ms")},
            {"expansion_ms", pass.value("expansion", 0.0)},
            {"shadow_ms", pass.value("shadow", 0.0)},
            {"main_ms", pass.value("main", 0.0)},
            {"truth_ms", pass.value("truth", 0.0)},
            {"main_lanes_per_covered_pixel", r.at("plant_draws").at("main").at("lanes_per_covered_pixel")},
            {"covered_pixels", r.at("covered_pixels")},
            {"plants_drawn", r.at("plants_drawn_per_lod")[0].get<double>() +
                                 r.at("plants_drawn_per_lod")[1].get<double>() +
                                 r.at("plants_drawn_per_lod")[2].get<double>()}};
}

nlohmann::json runGenerate(const SuiteOptions& options, const std::string&, nlohmann::json& parameters) {
    GenerateBenchOptions generate{.repeats = options.quick ? 1u : 3u, .device = options.device};
    parameters = {{"tile_size", generate.tileSize}, {"density", generate.density}, {"repeats", generate.repeats}};
    return benchGenerate(generate);
}

nlohmann::json runDataset(const SuiteOptions& options, const std::string& root, nlohmann::json& parameters) {
    DatasetBenchOptions dataset{.scenePath = root + "/examples/rover-track.json",
                                .resolution = options.quick ? "320x240" : "640x480",
                                .frames = options.quick ? 3u : 6u,
                                .device = options.device};
    parameters = {{"scene", "rover-track.json"},
                  {"resolution", *dataset.resolution},
                  {"frames", dataset.frames},
                  {"measured_frames", dataset.frames - 1}};
    return benchDataset(dataset);
}

nlohmann::json runCollide(const SuiteOptions& options, const std::string&, nlohmann::json& parameters) {
    CollideBenchOptions collide{.fields = {400},
                                .ticks = options.quick ? 10u : 30u,
                                .warmup = options.quick ? 2u : 5u,
                                .device = options.device};
    parameters = {{"fields", 400},
                  {"colliders_per_field", 25},
                  {"ticks", collide.ticks},
                  {"warmup", collide.warmup},
                  {"density", collide.density},
                  {"radius", collide.radius}};
    return benchCollide(collide);
}

nlohmann::json runWorld(const SuiteOptions& options, const std::string& root, nlohmann::json& parameters) {
    WorldBenchOptions world{.scenePath = root + "/examples/world.json", .device = options.device};
    if (options.quick) {
        world.densityMultiplier = 0.1f;
        world.tiles = 1;
        world.resident = {1, 4};
        world.width = 320, world.height = 180;
        world.frames = 1;
    }
    parameters = {{"scene", "world.json"},
                  {"density_multiplier", world.densityMultiplier > 0.0f ? nlohmann::json(world.densityMultiplier)
                                                                        : nlohmann::json("the scene's")},
                  {"tiles", world.tiles},
                  {"resident", world.resident},
                  {"resolution", sizeText(world.width, world.height)},
                  {"frames", world.frames}};
    return benchWorld(world);
}

nlohmann::json runLidar(const SuiteOptions& options, const std::string& root, nlohmann::json& parameters) {
    LidarBenchOptions lidar{.scenePath = root + "/examples/meadow.json", .sweeps = options.quick ? 3u : 10u};
    parameters = {{"scene", "meadow.json"}, {"preset", lidar.preset}, {"sweeps", lidar.sweeps}};
    return benchLidar(lidar);
}

const std::vector<Figure>& figures() {
    static const std::vector<Figure> list = {
        {"crosscheck", "correctness: the default frame's depth, disparity and labels against lavapipe's reference",
         [](const SuiteOptions& o, const std::string& root, nlohmann::json& parameters) {
             nlohmann::json result = suiteCrossCheck(root, o.device);
             parameters = result.at("parameters");
             return result;
         },
         [](const nlohmann::json& r) {
             return nlohmann::json{{"depth_equal", r["depth"]["equal_fraction"]},
                                   {"depth_within_1e-3", r["depth"]["within_1e-3_fraction"]},
                                   {"disparity_equal", r["disparity"]["equal_fraction"]},
                                   {"disparity_right_equal", r["disparity_right"]["equal_fraction"]},
                                   {"labels_equal", r["labels"]["equal_fraction"]},
                                   {"agrees", r["agrees"]},
                                   {"exact", r["exact"]}};
         }},
        {"generate", "tile generation: a 500 x 500 m tile of uniform grass, generated and uploaded", runGenerate,
         [](const nlohmann::json& r) {
             return nlohmann::json{{"plants", r.at("plants")},
                                   {"seconds", r.at("seconds")},
                                   {"plants_per_second", r.at("plants_per_second")},
                                   {"upload_seconds", r.value("upload_seconds", 0.0)},
                                   {"total_seconds", r.value("total_seconds", r.at("seconds").get<double>())}};
         }},
        {"frame_720p", "the default frame (meadow), every pass, 4x MSAA; lanes per covered pixel",
         [](const SuiteOptions& o, const std::string& root, nlohmann::json& p) {
             return o.quick ? runFrame(root + "/examples/meadow.json", 640, 360, 4, 1, o, p)
                            : runFrame(root + "/examples/meadow.json", 1280, 720, 4, 5, o, p);
         },
         frameSummary},
        {"frame_1080p", "the default frame (meadow) at the larger size, 4x MSAA",
         [](const SuiteOptions& o, const std::string& root, nlohmann::json& p) {
             return o.quick ? runFrame(root + "/examples/meadow.json", 960, 540, 4, 1, o, p)
                            : runFrame(root + "/examples/meadow.json", 1920, 1080, 4, 5, o, p);
         },
         frameSummary},
        {"bench_patch", "the bench patch (2^13 plants on one patch, near blades), 1x",
         [](const SuiteOptions& o, const std::string& root, nlohmann::json& p) {
             return o.quick ? runFrame(root + "/examples/bench-patch.json", 512, 384, 1, 1, o, p)
                            : runFrame(root + "/examples/bench-patch.json", 1024, 768, 1, 3, o, p);
         },
         frameSummary},
        {"dataset", "the rover-track dataset: stereo + truth + every file, frames per second", runDataset,
         [](const nlohmann::json& r) {
             return nlohmann::json{{"frames_per_second", r.at("frames_per_second")},
                                   {"seconds_per_frame", r.at("seconds_per_frame")},
                                   {"cpu_seconds_per_frame", r.at("cpu_seconds_per_frame")},
                                   {"bytes_per_frame", r.at("bytes_per_frame")}};
         }},
        {"collide", "interaction worst case: 400 fields x 25 colliders, CPU collision, upload and GPU recovery",
         runCollide,
         [](const nlohmann::json& r) {
             const nlohmann::json& c = r.at("results").at(0);
             return nlohmann::json{{"contacts", c.at("contacts")},
                                   {"cpu_collision_ms", c.at("cpu_collision_ms")},
                                   {"upload_ms", c.at("upload_ms")},
                                   {"gpu_recovery_ms", c.at("gpu_recovery_ms")},
                                   {"total_ms", c.at("total_ms")},
                                   {"idle_colliders_ms", r.at("idle_colliders_ms")},
                                   {"zero_active_recovery_dispatches", r.at("zero_active_recovery_dispatches")}};
         }},
        {"world", "world streaming: tile generation, resident memory, upload and frame time against resident tiles",
         runWorld,
         [](const nlohmann::json& r) {
             nlohmann::json s = {{"ms_per_tile", r.at("generation").at("ms_per_tile")},
                                 {"plants_per_second", r.at("generation").at("plants_per_second")},
                                 {"tile_bytes", r.at("tile_bytes")}};
             const nlohmann::json& gpu = r.at("gpu");
             if (gpu.is_object() && !gpu.at("rows").empty()) {
                 s["upload_ms_per_tile"] = gpu.at("rows").back().at("upload_ms_per_tile");
                 s["frame_ms_most_resident"] = gpu.at("rows").back().at("frame_ms");
                 bool same = true;
                 for (const nlohmann::json& row : gpu.at("rows")) same = same && row.at("same_image_as_one_tile");
                 s["same_image_as_one_tile"] = same;
             }
             return s;
         }},
        {"lidar", "LiDAR sweep (VLP-16) driving through the meadow, CPU (Embree)", runLidar,
         [](const nlohmann::json& r) {
             return nlohmann::json{{"sweep_ms", r.at("sweep_ms")},
                                   {"real_time_factor", r.at("real_time_factor")},
                                   {"points_per_second", r.at("points_per_second")}};
         },
         Component::Embree},
    };
    return list;
}

std::string utcNow() {
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&now, &tm);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return text;
}

void checkOptions(const SuiteOptions& options, const std::string& root) {
    require(!options.outDir.empty(), "--out: a folder is required");
    for (const std::string& name : options.only) {
        const std::vector<std::string>& names = suiteFigureNames();
        if (std::find(names.begin(), names.end(), name) != names.end()) continue;
        std::string known;
        for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
        throw Error("--only: no figure '" + name + "' (the figures: " + known + ")");
    }
    std::error_code ec;
    require(fs::is_regular_file(root + "/examples/meadow.json", ec),
            "--data: '" + root + "' holds no examples/meadow.json (the folder of examples/ and bench/reference/)");
    const bool usedFolder =
        fs::exists(options.outDir, ec) && !(fs::is_directory(options.outDir, ec) && fs::is_empty(options.outDir, ec));
    require(options.overwrite || !usedFolder, "--out: '" + options.outDir +
                                                  "' exists and is not an empty folder; use --overwrite to replace its "
                                                  "suite.json and suite.md, or choose another --out");
}

// One figure, timed; an error becomes its recorded failure (the suite goes on to the next figure).
nlohmann::json runFigure(const Figure& figure, const SuiteOptions& options, const std::string& root) {
    nlohmann::json out = {{"description", figure.description}, {"parameters", nlohmann::json::object()}};
    const std::vector<std::string>& only = options.only;
    if (!only.empty() && std::find(only.begin(), only.end(), figure.name) == only.end()) {
        out["status"] = "skipped";
        out["reason"] = "not selected by --only";
        return out;
    }
    if (figure.needs && !hasComponent(*figure.needs)) {
        out["status"] = "skipped";
        try { // the lean build's one wording: "the lidar figure needs Embree, which this build ... leaves out (...)"
            requireComponent(*figure.needs, std::string("the ") + figure.name + " figure");
        } catch (const Error& e) {
            out["reason"] = e.what();
        }
        return out;
    }
    std::fprintf(stderr, "sward-bench suite: %s ...\n", figure.name);
    const Stopwatch watch;
    nlohmann::json parameters = nlohmann::json::object(); // set before the benchmark starts: kept when it fails
    try {
        nlohmann::json result = figure.run(options, root, parameters);
        out["summary"] = figure.summary(result);
        out["result"] = std::move(result);
        out["status"] = "measured";
    } catch (const std::exception& e) {
        out["status"] = "failed";
        out["reason"] = e.what();
    }
    out["parameters"] = parameters;
    out["seconds"] = watch.seconds();
    std::fprintf(stderr, "sward-bench suite: %s %s in %.1f s\n", figure.name, out["status"].get<std::string>().c_str(),
                 out["seconds"].get<double>());
    return out;
}

nlohmann::json deviceRecord(const std::string& device) {
    const Device chosen(DeviceOptions{.deviceFilter = device, .validation = false, .quiet = true});
    return suiteDeviceJson(chosen);
}

} // namespace

const std::vector<std::string>& suiteFigureNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> out;
        for (const Figure& f : figures()) out.push_back(f.name);
        return out;
    }();
    return names;
}

std::string suiteDataRoot() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const fs::path installed = exe.parent_path().parent_path() / "share" / "sward";
        if (fs::is_regular_file(installed / "examples" / "meadow.json", ec)) return installed.string();
    }
    return SWARD_SOURCE_DIR;
}

nlohmann::json runBenchSuite(const SuiteOptions& options) {
    const std::string root = options.dataRoot.empty() ? suiteDataRoot() : options.dataRoot;
    checkOptions(options, root);
    StagedFolder folder(options.outDir, "suite folder"); // locks --out for the whole run
    const Stopwatch watch;
    nlohmann::json suite = {{"format", kSuiteFormat},
                            {"mode", options.quick ? "quick" : "full"},
                            {"sward_revision", SWARD_REVISION},
                            {"date_utc", utcNow()},
                            {"data_root", root},
                            {"host", {{"cpu_threads", std::thread::hardware_concurrency()}}},
                            {"device", deviceRecord(options.device)}};
    nlohmann::json figuresJson = nlohmann::json::object();
    for (const Figure& figure : figures()) figuresJson[figure.name] = runFigure(figure, options, root);
    suite["figures"] = std::move(figuresJson);
    suite["seconds"] = watch.seconds();
    suite["passed"] = suitePassed(suite);
    writeTextAtomically(folder.path() + "/suite.json", suite.dump(2) + "\n");
    writeTextAtomically(folder.path() + "/suite.md", suiteTable(suite));
    folder.commit();
    return suite;
}

bool suitePassed(const nlohmann::json& suite) {
    for (const auto& [name, figure] : suite.at("figures").items()) {
        if (figure.at("status") == "failed") return false;
        if (name == "crosscheck" && figure.at("status") == "measured" && !figure.at("result").at("agrees").get<bool>())
            return false;
    }
    return true;
}

} // namespace sward

// Rolling shutter (render/rolling_shutter.h): each row of every image (colour and truth) is that of a global-shutter
// render at the row's readout time, a vertical pole seen from a camera moving sideways slants by the predicted
// amount, and sward-render's shards and resumed runs write the whole run's files.
#include "gpu_test.h"

#include "render/rolling_shutter.h"
#include "render/scene_gpu.h"
#include "render/scene_renderer.h"
#include "render/sequence_frame.h"
#include "scene/scene_input.h"
#include "scene/scene_resources.h"

#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>

using namespace sward;

namespace {

using RollingShutterTest = sward::test::GpuTest;

// Rows [first, end) of an image of `height` rows, as bytes.
template <class T> std::string rowBytes(const std::vector<T>& image, uint32_t height, uint32_t first, uint32_t end) {
    const size_t perRow = image.size() / height;
    return std::string(reinterpret_cast<const char*>(image.data() + first * perRow),
                       (end - first) * perRow * sizeof(T));
}

// A 0.2 x 0.2 m square pole, 60 m tall, its base at the model's origin (glTF: y up).
std::string writePole(const std::string& dir) {
    const float p[24] = {-0.1f, 0,  -0.1f, 0.1f, 0,  -0.1f, 0.1f, 0,  0.1f, -0.1f, 0,  0.1f,
                         -0.1f, 60, -0.1f, 0.1f, 60, -0.1f, 0.1f, 60, 0.1f, -0.1f, 60, 0.1f};
    // Four sides, both windings (drawn from anywhere).
    std::vector<uint16_t> idx;
    for (uint16_t s = 0; s < 4; ++s) {
        const uint16_t a = s, b = uint16_t((s + 1) % 4), c = uint16_t(b + 4), d = uint16_t(a + 4);
        for (uint16_t v : {a, b, c, a, c, d, a, c, b, a, d, c}) idx.push_back(v);
    }
    std::vector<uint8_t> bytes(sizeof p + idx.size() * 2);
    std::memcpy(bytes.data(), p, sizeof p);
    std::memcpy(bytes.data() + sizeof p, idx.data(), idx.size() * 2); // 96 + 96 bytes: a multiple of 3
    static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string b64;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const uint32_t v = uint32_t(bytes[i]) << 16 | uint32_t(bytes[i + 1]) << 8 | bytes[i + 2];
        for (int k = 0; k < 4; ++k) b64 += alphabet[(v >> (18 - 6 * k)) & 63];
    }
    const std::string path = dir + "/pole.gltf";
    std::ofstream(path) << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "pole", "mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
                       "min": [-0.1, 0, -0.1], "max": [0.1, 60, 0.1]},
                      {"bufferView": 1, "componentType": 5123, "count": 48, "type": "SCALAR"}],
        "bufferViews": [{"buffer": 0, "byteLength": 96}, {"buffer": 0, "byteOffset": 96, "byteLength": 96}],
        "buffers": [{"byteLength": 192, "uri": "data:application/octet-stream;base64,)"
                        << b64 << R"("}]})";
    return path;
}

} // namespace

TEST(RollingShutter, EveryRowIsReadAtItsOwnTime) {
    const double t = 1.0, readout = 0.03;
    const std::vector<ReadoutBand> rows = readoutBands(t, readout, 48, 0);
    ASSERT_EQ(rows.size(), 48u);
    for (uint32_t r = 0; r < 48; ++r) {
        EXPECT_EQ(rows[r].firstRow, r);
        EXPECT_EQ(rows[r].endRow, r + 1);
        EXPECT_EQ(rows[r].time, readoutRowTime(t, readout, r, 48)); // bitwise: the tests' references use it
    }
    EXPECT_DOUBLE_EQ(rows.front().time, t - readout / 2 + readout / 96);
    EXPECT_DOUBLE_EQ(rows.back().time, t + readout / 2 - readout / 96);
    EXPECT_DOUBLE_EQ(readoutRowTime(t, readout, 24, 48) + readoutRowTime(t, readout, 23, 48), 2 * t); // t: the middle
    EXPECT_EQ(readoutBands(t, readout, 48, 100).size(), 48u); // more bands than rows: every row
}

TEST(RollingShutter, BandsPartitionTheRowsAtTheirMiddleTimes) {
    const double t = 0.4, readout = 0.05;
    const std::vector<ReadoutBand> bands = readoutBands(t, readout, 48, 5);
    ASSERT_EQ(bands.size(), 5u);
    uint32_t next = 0;
    for (const ReadoutBand& band : bands) {
        EXPECT_EQ(band.firstRow, next);
        EXPECT_GT(band.endRow, band.firstRow);
        next = band.endRow;
        double mean = 0.0; // the mean of its rows' times
        for (uint32_t r = band.firstRow; r < band.endRow; ++r) mean += readoutRowTime(t, readout, r, 48);
        EXPECT_NEAR(band.time, mean / (band.endRow - band.firstRow), 1e-15);
    }
    EXPECT_EQ(next, 48u);
    EXPECT_EQ(bands[0].endRow, 9u);
    EXPECT_EQ(readoutBands(t, readout, 48, 1)[0].time, t); // one band: a global shutter
}

TEST(RollingShutter, CopyRowsCopiesEveryImageItHas) {
    FrameImages from{.width = 2, .height = 3}, to;
    from.depth = {1, 2, 3, 4, 5, 6};
    from.normals.assign(18, 7.0f);
    from.labels = {1, 2, 3, 4, 5, 6};
    copyRows(from, to, 1, 2);
    EXPECT_EQ(to.depth, (std::vector<float>{0, 0, 3, 4, 0, 0}));
    EXPECT_EQ(to.labels, (std::vector<uint32_t>{0, 0, 3, 4, 0, 0}));
    EXPECT_EQ(std::count(to.normals.begin(), to.normals.end(), 7.0f), 6);
    EXPECT_TRUE(to.rgbaHalf.empty()); // none in `from`
}

// A camera on a path at 10 m/s with a 50 ms readout in 12 bands (stereo, plants, flow; no simulation): rows of the
// colour, depth, labels, normals and flow of both views are bitwise those of a global-shutter render at the row's
// band's time, with the flow's rigs a step before and after it.
TEST_F(RollingShutterTest, RowsAreThoseOfAGlobalShutterRenderAtTheirTime) {
    constexpr uint32_t kW = 64, kH = 48;
    const nlohmann::json overrides = {{"render.resolution", {kW, kH}},
                                      {"render.samples", 1},
                                      {"render.flow", true},
                                      {"vehicles", nlohmann::json::array()},
                                      {"camera.path", {{"points", {{53.5, 46.0}, {51.0, 50.0}}}, {"speed", 10.0}}},
                                      {"camera.sensor", {{"readout_s", 0.05}, {"readout_bands", 12}}}};
    SceneResources r =
        buildSceneResources(loadSceneInput({.path = std::string(SWARD_TEST_DATA_DIR) + "/dataset_scene.json",
                                            .overrides = overrides.dump()}),
                            true);
    RigCameras cameras;
    const std::optional<SensorModel> sensor = checkRigAndSensor(r, kW, kH, 0, cameras);
    ASSERT_TRUE(sensor);
    SceneGpu gpu = createSceneGpu(*ctx, r, 1, SimulationMode::WhenSceneHasColliders);
    ASSERT_FALSE(gpu.simulation);
    OffscreenFrame target(*ctx, kW, kH, 1, true);
    const uint32_t frame = 2;
    const double t = frame * r.scene.sequence.timeStep, dt = r.scene.sequence.timeStep;
    const FrameImages rolling = renderSequenceFrame(gpu, target, r, kW, kH, frame, 0.0, sensor, cameras);
    ASSERT_EQ(ctx->device.validationMessageCount(), 0u);
    const std::vector<ReadoutBand> bands = readoutBands(t, 0.05, kH, 12);
    // A global-shutter render at `time` with the flow's rigs a step before and after it.
    auto globalAt = [&](double time) {
        const RigCameras rig = sequenceRigAt(r, kW, kH, time);
        const RigCameras previous = sequenceRigAt(r, kW, kH, time - dt), next = sequenceRigAt(r, kW, kH, time + dt);
        const FlowTicks flow{
            .previous = {&previous.left, &previous.right}, .next = {&next.left, &next.right}, .timeStep = dt};
        return target.render(*gpu.renderer, rig.left, time, frame, {}, &rig.right, &flow);
    };
    const FrameImages global = globalAt(t);
    for (uint32_t row : {0u, 1u, 17u, 30u, 47u}) {
        const ReadoutBand& band = bands[row / 4];
        ASSERT_TRUE(row >= band.firstRow && row < band.endRow);
        FrameImages ref = globalAt(band.time);
        sensor->applyHalf(r.scene.seed, frame, 0, ref.rgbaHalf);
        sensor->applyHalf(r.scene.seed, frame, 1, ref.rightRgbaHalf);
        auto same = [&](const auto& a, const auto& b) {
            return rowBytes(a, kH, row, row + 1) == rowBytes(b, kH, row, row + 1);
        };
        EXPECT_TRUE(same(rolling.rgbaHalf, ref.rgbaHalf)) << "row " << row;
        EXPECT_TRUE(same(rolling.rightRgbaHalf, ref.rightRgbaHalf)) << "row " << row;
        EXPECT_TRUE(same(rolling.depth, ref.depth)) << "row " << row;
        EXPECT_TRUE(same(rolling.rightDepth, ref.rightDepth)) << "row " << row;
        EXPECT_TRUE(same(rolling.labels, ref.labels)) << "row " << row;
        EXPECT_TRUE(same(rolling.rightLabels, ref.rightLabels)) << "row " << row;
        EXPECT_TRUE(same(rolling.normals, ref.normals)) << "row " << row;
        EXPECT_TRUE(same(rolling.flowForward, ref.flowForward)) << "row " << row;
        EXPECT_TRUE(same(rolling.flowBackward, ref.flowBackward)) << "row " << row;
        EXPECT_TRUE(same(rolling.rightFlowForward, ref.rightFlowForward)) << "row " << row;
        // The test can fail: the lower rows (the ground; the top rows are sky) are not those of the frame's instant.
        if (row == 30 || row == 47) {
            EXPECT_FALSE(same(rolling.depth, global.depth)) << "row " << row;
            EXPECT_FALSE(same(rolling.rgbaHalf, global.rgbaHalf)) << "row " << row;
        }
    }
}

// A camera moving sideways at v sees a vertical pole at depth Z: row r is read at t_r, when the camera has moved
// v (t_r - t), so the pole's edge shifts by fx v (t_r - t) / Z along the row; from the first to the last row
// fx v readout (H - 1) / (H Z). Every row its own band; the pole's left edge per row from the labels, fitted by least
// squares (the pixel grid's steps average out).
TEST_F(RollingShutterTest, PoleIsSlantedByTheReadout) {
    constexpr uint32_t kW = 96, kH = 64;
    const std::string dir = sward::test::tempDir("rolling-shutter-pole");
    writePole(dir);
    nlohmann::json scene = nlohmann::json::parse(sward::test::readFile(SWARD_TEST_DATA_DIR "/dataset_scene.json"));
    scene["render"]["resolution"] = {kW, kH};
    scene["render"]["samples"] = 1;
    scene["vehicles"] = nlohmann::json::array();
    const glm::dvec3 eye(50.0, 40.0, 30.0);
    const double Z = 10.0, v = 10.0, readout = 0.05, fovY = 20.0;
    // The pole's front face at depth Z, its left edge 0.4 m right of the optical axis (the silhouette is that edge).
    scene["objects"] = {{{"name", "pole"},
                         {"model", "pole.gltf"},
                         {"align_to_terrain", false},
                         {"path", {{"points", {{eye.x + 0.5, eye.y + Z + 0.1}}}, {"height_above_ground", -5.0}}}}};
    std::ofstream(dir + "/scene.json") << scene.dump();
    SceneResources r = buildSceneResources(loadSceneInput({.path = dir + "/scene.json"}), false);
    SceneGpu gpu = createSceneGpu(*ctx, r, 1, SimulationMode::None);
    OffscreenFrame target(*ctx, kW, kH, 1);
    auto rigAt = [&](double t) {
        const glm::dvec3 p = eye + glm::dvec3(v * t, 0.0, 0.0);
        const Camera c = Camera::lookAt(p, p + glm::dvec3(0, 1, 0), {0, 0, 1}, fovY, kW, kH);
        return RigCameras{c, c};
    };
    const double t = 0.0;
    auto labelsAt = [&](const std::vector<ReadoutBand>& bands) {
        auto colourAt = [&](double time, bool) {
            return renderBandColour(*gpu.renderer, target, rigAt, false, time, 0.0, 0, 0.0, 0, {});
        };
        auto truthAt = [&](double time, bool) {
            return target.render(*gpu.renderer, rigAt(time).left, time, 0, {}, nullptr, nullptr, false);
        };
        return composeReadout(bands, kW, kH, colourAt, truthAt).labels;
    };
    // The slope (pixels per row) of the pole's left edge: the first column labelled as the object in each row.
    auto slope = [&](const std::vector<uint32_t>& labels) {
        double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
        for (uint32_t y = 0; y < kH; ++y)
            for (uint32_t x = 0; x < kW; ++x)
                if ((labels[y * kW + x] >> 24) == 8) { // the semantic class "object"
                    n += 1, sx += y, sy += x, sxx += double(y) * y, sxy += double(y) * x;
                    break;
                }
        EXPECT_EQ(n, double(kH)); // the pole spans every row
        return (n * sxy - sx * sy) / (n * sxx - sx * sx);
    };
    const double fx = rigAt(0.0).left.fx;
    const double predicted = fx * v * readout * (kH - 1) / kH / Z; // pixels from the first row to the last
    const double slanted = slope(labelsAt(readoutBands(t, readout, kH, 0))) * (kH - 1);
    const double upright = slope(labelsAt(readoutBands(t, 0.0, kH, 1))) * (kH - 1);
    // The camera moves right: what is seen later (lower rows) sits further left.
    EXPECT_NEAR(-slanted, predicted, 0.5) << "predicted " << predicted << " px";
    EXPECT_NEAR(upright, 0.0, 0.5);
    EXPECT_GT(predicted, 5.0);
}

// sward-render with a rolling shutter in 4 bands and a shutter (noise too): two shards, and a run resumed after lost
// files, write the whole run's files; frames.jsonl has each frame's readout. And readout_s 0 writes the very files
// of a scene without the key.
TEST(RollingShutterDataset, ShardsAndResumedRunsWriteTheWholeRunsFiles) {
    nlohmann::json scene = nlohmann::json::parse(sward::test::readFile(SWARD_TEST_DATA_DIR "/dataset_scene.json"));
    scene["render"]["resolution"] = {64, 48};
    scene["render"]["samples"] = 1;
    scene["camera"]["path"] = {{"points", {{53.5, 46.0}, {51.0, 50.0}}}, {"speed", 4.0}};
    const std::string dir = sward::test::tempDir("rolling-shutter-shards");
    auto write = [&](const std::string& name, const nlohmann::json& sensor) {
        scene["camera"]["sensor"] = sensor;
        std::ofstream(dir + "/" + name) << scene.dump();
        return dir + "/" + name;
    };
    const std::string path = write("scene.json", {{"readout_s", 0.03},
                                                  {"readout_bands", 4},
                                                  {"shutter_s", 0.01},
                                                  {"motion_samples", 2},
                                                  {"electrons_per_unit", 500}});
    std::string err;
    ASSERT_EQ(sward::test::runSwardRender(path + " --out " + dir + "/whole --frames 0:3", err), 0) << err;
    for (const char* shard : {"0/2", "1/2"})
        ASSERT_EQ(sward::test::runSwardRender(path + " --out " + dir + "/parts --frames 0:3 --shard " + shard, err), 0)
            << err;
    EXPECT_GT(sward::test::expectSameRunFiles(dir + "/whole", dir + "/parts"), 3u * 18);
    std::filesystem::remove(dir + "/parts/left/000001.exr");
    std::filesystem::remove(dir + "/parts/depth/000002.exr");
    ASSERT_EQ(sward::test::runSwardRender(path + " --out " + dir + "/parts --frames 0:3", err), 0) << err;
    sward::test::expectSameRunFiles(dir + "/whole", dir + "/parts");
    const std::string frames = sward::test::readFile(dir + "/whole/frames.jsonl");
    const nlohmann::json first = nlohmann::json::parse(frames.substr(0, frames.find('\n')));
    ASSERT_TRUE(first.contains("readout")) << first.dump();
    EXPECT_EQ(first["readout"]["bands"], 4);
    EXPECT_DOUBLE_EQ(first["readout"]["first_row"]["time"].get<double>(), -0.03 * 0.5 + 0.03 * 6 / 48.0);
    EXPECT_NE(first["readout"]["first_row"]["left_pose"], first["readout"]["last_row"]["left_pose"]);
    EXPECT_EQ(first["sensor"]["readout_s"], 0.03);
    // readout_s 0: a global shutter, the very files of a sensor without the key.
    const std::string zero = write("zero.json", {{"readout_s", 0.0}, {"electrons_per_unit", 500}});
    const std::string none = write("none.json", {{"electrons_per_unit", 500}});
    ASSERT_EQ(sward::test::runSwardRender(zero + " --out " + dir + "/zero --frames 0:2", err), 0) << err;
    ASSERT_EQ(sward::test::runSwardRender(none + " --out " + dir + "/none --frames 0:2", err), 0) << err;
    EXPECT_GT(sward::test::expectSameRunFiles(dir + "/zero", dir + "/none"), 2u * 10);
}

// The keys: parsed with their ranges, refused with one error naming the key, written back for frames.jsonl (absent
// with a global shutter, so its records stay as they were).
TEST(RollingShutter, KeysAreCheckedAndWrittenBack) {
    const SensorParams p = parseSensor({{"readout_s", 0.03}, {"readout_bands", 16}}, "scene.json", "camera.sensor");
    EXPECT_EQ(p.readoutSeconds, 0.03);
    EXPECT_EQ(p.readoutBands, 16u);
    const nlohmann::json back = sensorToJson(p);
    EXPECT_EQ(back["readout_s"], 0.03);
    EXPECT_EQ(back["readout_bands"], 16);
    EXPECT_EQ(parseSensor(back, "scene.json", "camera.sensor").readoutBands, 16u); // the parser's keys
    EXPECT_FALSE(sensorToJson(parseSensor({{"readout_s", 0.03}}, "s", "camera.sensor")).contains("readout_bands"));
    const nlohmann::json global = sensorToJson(parseSensor({{"readout_s", 0.0}}, "s", "camera.sensor"));
    EXPECT_FALSE(global.contains("readout_s"));
    EXPECT_FALSE(global.contains("readout_bands"));
    auto error = [](const nlohmann::json& keys) {
        try {
            parseSensor(keys, "scene.json", "camera.sensor");
        } catch (const std::exception& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(error({{"readout_s", -0.01}}),
              "scene.json: 'camera.sensor.readout_s' must be between 0 and 1 (got -0.01)");
    EXPECT_EQ(error({{"readout_s", 1.5}}), "scene.json: 'camera.sensor.readout_s' must be between 0 and 1 (got 1.5)");
    EXPECT_EQ(error({{"readout_bands", 0}}),
              "scene.json: 'camera.sensor.readout_bands' must be an integer in [1, 16384] (got 0)");
    EXPECT_EQ(error({{"readout_bands", 3.5}}),
              "scene.json: 'camera.sensor.readout_bands' must be an integer in [1, 16384] (got 3.5)");
    EXPECT_EQ(error({{"readout_bands", 20000}}),
              "scene.json: 'camera.sensor.readout_bands' must be an integer in [1, 16384] (got 20000)");
}

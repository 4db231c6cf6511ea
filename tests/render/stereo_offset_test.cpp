// An unsynchronised stereo rig (camera.sensor.stereo_offset_s, render/sequence_frame.h): the right view and its truth
// are the synchronised rig's at the right camera's time (with a shutter and a rolling shutter too: its rows at their
// offset times), the left view and its truth stay the synchronised render's, and sward-render's shards and resumed runs
// write the whole run's files, whose right files are the synchronised dataset's a frame later.
#include "gpu_test.h"

#include "dataset/frame_record.h"
#include "render/motion_blur.h"
#include "render/rolling_shutter.h"
#include "render/scene_gpu.h"
#include "render/scene_renderer.h"
#include "render/sequence_frame.h"
#include "scene/scene.h"
#include "scene/scene_input.h"
#include "scene/scene_resources.h"

#include <nlohmann/json.hpp>

#include <filesystem>

using namespace sward;

namespace {

using StereoOffsetTest = sward::test::GpuTest;

constexpr uint32_t kW = 64, kH = 48;
// A time step and an offset of two steps that are exact in binary: the right camera's time t + offset is then
// bitwise the time of frame f + 2, so the synchronised render of that frame is the reference.
constexpr double kStep = 0.25, kOffset = 0.5;
constexpr uint32_t kFrame = 1, kLater = 3;

// The test dataset's scene at 64 x 48 without its vehicle (no simulation), the camera on a path at 10 m/s.
SceneResources movingRig(const nlohmann::json& sensor, bool flow) {
    const nlohmann::json overrides = {{"render.resolution", {kW, kH}},
                                      {"render.samples", 1},
                                      {"render.flow", flow},
                                      {"sequence.time_step", kStep},
                                      {"vehicles", nlohmann::json::array()},
                                      {"camera.path", {{"points", {{53.5, 46.0}, {51.0, 50.0}}}, {"speed", 10.0}}},
                                      {"camera.sensor", sensor}};
    return buildSceneResources(loadSceneInput({.path = std::string(SWARD_TEST_DATA_DIR) + "/dataset_scene.json",
                                               .overrides = overrides.dump()}),
                               true);
}

// The same sensor as a synchronised rig's.
std::optional<SensorModel> synchronised(const SensorModel& sensor, const Camera& left) {
    SensorParams params = sensor.params();
    params.stereoOffsetSeconds = 0.0;
    return SensorModel(params, Intrinsics::of(left));
}

// Every image of the left view, and of the right view, of `a` and `b` bitwise the same (those `a` has).
void expectSameLeft(const FrameImages& a, const FrameImages& b) {
    EXPECT_FALSE(a.depth.empty());
    EXPECT_EQ(a.rgbaHalf, b.rgbaHalf);
    EXPECT_EQ(a.depth, b.depth);
    EXPECT_EQ(a.labels, b.labels);
    EXPECT_EQ(a.normals, b.normals);
    EXPECT_EQ(a.flowForward, b.flowForward);
    EXPECT_EQ(a.flowBackward, b.flowBackward);
    EXPECT_EQ(a.motionBlur, b.motionBlur);
}
void expectSameRight(const FrameImages& a, const FrameImages& b) {
    EXPECT_FALSE(a.rightDepth.empty());
    EXPECT_EQ(a.rightRgbaHalf, b.rightRgbaHalf);
    EXPECT_EQ(a.rightDepth, b.rightDepth);
    EXPECT_EQ(a.rightLabels, b.rightLabels);
    EXPECT_EQ(a.rightNormals, b.rightNormals);
    EXPECT_EQ(a.rightFlowForward, b.rightFlowForward);
    EXPECT_EQ(a.rightFlowBackward, b.rightFlowBackward);
}

// Row `row` of an image of kH rows, as bytes.
template <class T> std::string rowBytes(const std::vector<T>& image, uint32_t row) {
    const size_t perRow = image.size() / kH;
    return std::string(reinterpret_cast<const char*>(image.data() + row * perRow), perRow * sizeof(T));
}

// Renders frame kFrame with the offset and frames kFrame and kLater synchronised; checks the left view and truth are
// the synchronised frame's, the right's the synchronised frame kLater's, the occlusion depths each the other view's
// at the view's own time, and the rig's right camera that of frame kLater. Returns the offset render.
FrameImages expectViewsAtTheirTimes(Context& ctx, const nlohmann::json& sensorKeys, bool flow) {
    SceneResources r = movingRig(sensorKeys, flow);
    RigCameras cameras;
    const std::optional<SensorModel> sensor = checkRigAndSensor(r, kW, kH, 0, cameras);
    EXPECT_TRUE(sensor);
    EXPECT_EQ(sensor->params().stereoOffsetSeconds, kOffset);
    SceneGpu gpu = createSceneGpu(ctx, r, 1, SimulationMode::WhenSceneHasColliders);
    EXPECT_FALSE(gpu.simulation);
    OffscreenFrame target(ctx, kW, kH, 1, flow);
    const std::optional<SensorModel> sync = synchronised(*sensor, cameras.left);
    RigCameras offsetRig, now, later;
    const FrameImages offset = renderSequenceFrame(gpu, target, r, kW, kH, kFrame, 0.0, sensor, offsetRig);
    const FrameImages atFrame = renderSequenceFrame(gpu, target, r, kW, kH, kFrame, 0.0, sync, now);
    const FrameImages atLater = renderSequenceFrame(gpu, target, r, kW, kH, kLater, 0.0, sync, later);
    EXPECT_EQ(ctx.device.validationMessageCount(), 0u);
    expectSameLeft(offset, atFrame);
    expectSameRight(offset, atLater);
    EXPECT_EQ(offset.rightDepthAtLeftTime, atFrame.rightDepth);
    EXPECT_EQ(offset.leftDepthAtRightTime, atLater.depth);
    EXPECT_TRUE(atFrame.rightDepthAtLeftTime.empty()); // a synchronised rig's masks use its own views
    EXPECT_EQ(offsetRig.left.position, now.left.position);
    EXPECT_EQ(offsetRig.right.position, later.right.position);
    // The test can fail: the camera moves 5 m over the offset, so the right view is not the frame's instant's.
    EXPECT_NE(offset.rightDepth, atFrame.rightDepth);
    EXPECT_NE(offset.rightRgbaHalf, atFrame.rightRgbaHalf);
    return offset;
}

} // namespace

// A global shutter with flow: both views' colour, depth, labels, normals and flow, each at its own camera's time.
TEST_F(StereoOffsetTest, RightViewIsTheSynchronisedRigsAtTheRightCamerasTime) {
    expectViewsAtTheirTimes(*ctx, {{"stereo_offset_s", kOffset}}, true);
}

// A rolling shutter in 4 bands and a shutter of 2 sub-frames: the right camera's readout is its own, around its time;
// three of its rows are those of a global-shutter truth render at their band's time of that readout (t + offset).
TEST_F(StereoOffsetTest, RightRowsAreReadAtTheirOffsetTimesWithAShutter) {
    const double readout = 0.05, shutter = 0.01;
    const FrameImages offset = expectViewsAtTheirTimes(*ctx,
                                                       {{"stereo_offset_s", kOffset},
                                                        {"readout_s", readout},
                                                        {"readout_bands", 4},
                                                        {"shutter_s", shutter},
                                                        {"motion_samples", 2}},
                                                       false);
    EXPECT_FALSE(offset.motionBlur.empty());
    SceneResources r = movingRig({{"stereo_offset_s", kOffset}}, false);
    SceneGpu gpu = createSceneGpu(*ctx, r, 1, SimulationMode::WhenSceneHasColliders);
    OffscreenFrame target(*ctx, kW, kH, 1);
    const double rightTime = kFrame * kStep + kOffset;
    const std::vector<ReadoutBand> bands = readoutBands(rightTime, readout, kH, 4);
    for (uint32_t row : {2u, 30u, 45u}) {
        const ReadoutBand& band = bands[row / 12];
        ASSERT_TRUE(row >= band.firstRow && row < band.endRow);
        const RigCameras rig = sequenceRigAt(r, kW, kH, band.time);
        const FrameImages global =
            target.render(*gpu.renderer, rig.left, band.time, kFrame, {}, &rig.right, nullptr, false);
        EXPECT_EQ(rowBytes(offset.rightDepth, row), rowBytes(global.rightDepth, row)) << "row " << row;
        EXPECT_EQ(rowBytes(offset.rightLabels, row), rowBytes(global.rightLabels, row)) << "row " << row;
        EXPECT_EQ(rowBytes(offset.rightNormals, row), rowBytes(global.rightNormals, row)) << "row " << row;
        // Not the left camera's row time (t without the offset): the ground rows differ.
        if (row >= 30) {
            const RigCameras leftRig = sequenceRigAt(r, kW, kH, band.time - kOffset);
            const FrameImages early = target.render(*gpu.renderer, leftRig.left, band.time - kOffset, kFrame, {},
                                                    &leftRig.right, nullptr, false);
            EXPECT_NE(rowBytes(offset.rightDepth, row), rowBytes(early.rightDepth, row)) << "row " << row;
        }
    }
}

// The right view of an unsynchronised rig sees the plants of the frame's own interaction tick, as a shutter's
// sub-frames and a readout's bands do, not those of the tick at its time: the test scene's rover presses the grass in
// view of a fixed rig, without wind, so over the offset of two ticks only its tracks change. The right truth of frame 1
// is the synchronised frame 1's, and differs from frame 3's (the rover pressed more plants by then).
TEST_F(StereoOffsetTest, RightViewSeesTheFramesOwnPressedPlants) {
    const nlohmann::json overrides = {{"render.resolution", {kW, kH}},
                                      {"render.samples", 1},
                                      {"sequence.time_step", kStep},
                                      {"wind", {{"strength", 0.0}, {"gust_strength", 0.0}, {"flutter", 0.0}}},
                                      {"camera.sensor", {{"stereo_offset_s", kOffset}}}};
    // Each sequence from frame 0 on, with its own resources and GPU scene (which takes them over): the rover's
    // simulation ticks once per frame rendered. `synchronise`: the same sensor without the offset.
    auto frames = [&](bool synchronise, uint32_t last) {
        SceneResources r =
            buildSceneResources(loadSceneInput({.path = std::string(SWARD_TEST_DATA_DIR) + "/dataset_scene.json",
                                                .overrides = overrides.dump()}),
                                true);
        RigCameras rig;
        std::optional<SensorModel> sensor = checkRigAndSensor(r, kW, kH, 0, rig);
        EXPECT_TRUE(sensor);
        if (synchronise) sensor = synchronised(*sensor, rig.left);
        SceneGpu gpu = createSceneGpu(*ctx, r, 1, SimulationMode::WhenSceneHasColliders);
        EXPECT_TRUE(gpu.simulation);
        OffscreenFrame target(*ctx, kW, kH, 1);
        std::vector<FrameImages> images;
        for (uint32_t f = 0; f <= last; ++f)
            images.push_back(renderSequenceFrame(gpu, target, r, kW, kH, f, 0.0, sensor, rig));
        return images;
    };
    const std::vector<FrameImages> offset = frames(false, kFrame), synced = frames(true, kLater);
    EXPECT_EQ(offset[kFrame].depth, synced[kFrame].depth);
    EXPECT_EQ(offset[kFrame].rightDepth, synced[kFrame].rightDepth);
    EXPECT_EQ(offset[kFrame].rightLabels, synced[kFrame].rightLabels);
    EXPECT_EQ(offset[kFrame].rightNormals, synced[kFrame].rightNormals);
    // The test can fail: the right camera sees the rover's tracks grow between the two ticks.
    EXPECT_NE(synced[kFrame].rightDepth, synced[kLater].rightDepth);
}

// sward-render with an offset of one frame: two shards, and a run resumed after lost files, write the whole run's
// files; the left files (and occlusion/) are the synchronised dataset's of the same frame, the right ones (and
// occlusion_right/) of the next frame. And stereo_offset_s 0 writes the very files of a scene without the key.
TEST(StereoOffsetDataset, ShardsResumedRunsAndTheSynchronisedDatasetAgree) {
    nlohmann::json scene = nlohmann::json::parse(sward::test::readFile(SWARD_TEST_DATA_DIR "/dataset_scene.json"));
    scene["render"]["resolution"] = {64, 48};
    scene["render"]["samples"] = 1;
    scene["sequence"]["time_step"] = kStep;
    scene["camera"]["path"] = {{"points", {{53.5, 46.0}, {51.0, 50.0}}}, {"speed", 4.0}};
    const std::string dir = sward::test::tempDir("stereo-offset-shards");
    auto write = [&](const std::string& name, const nlohmann::json& sensor) {
        scene["camera"]["sensor"] = sensor;
        return sward::test::writeSceneFile(dir, name, scene.dump());
    };
    const std::string path = write("scene", {{"stereo_offset_s", kStep}});
    std::string err;
    ASSERT_EQ(sward::test::runSwardRender(path + " --out " + dir + "/whole --frames 0:2", err), 0) << err;
    for (const char* shard : {"0/2", "1/2"})
        ASSERT_EQ(sward::test::runSwardRender(path + " --out " + dir + "/parts --frames 0:2 --shard " + shard, err), 0)
            << err;
    EXPECT_GE(sward::test::expectSameRunFiles(dir + "/whole", dir + "/parts"), 2u * 18);
    std::filesystem::remove(dir + "/parts/right/000001.exr");
    std::filesystem::remove(dir + "/parts/occlusion_right/000000.png");
    ASSERT_EQ(sward::test::runSwardRender(path + " --out " + dir + "/parts --frames 0:2", err), 0) << err;
    sward::test::expectSameRunFiles(dir + "/whole", dir + "/parts");
    // Each view's files are the synchronised rig's at its camera's time.
    const std::string sync = write("sync", nlohmann::json::object());
    ASSERT_EQ(sward::test::runSwardRender(sync + " --out " + dir + "/sync --frames 0:3", err), 0) << err;
    auto file = [&](const std::string& run, const char* folder, uint32_t frame, const char* extension) {
        char name[32];
        std::snprintf(name, sizeof name, "/%06u", frame);
        return sward::test::readFile(dir + "/" + run + "/" + folder + name + extension);
    };
    for (uint32_t frame : {0u, 1u}) {
        for (const char* folder : {"left", "depth", "normal", "disparity"})
            EXPECT_EQ(file("whole", folder, frame, ".exr"), file("sync", folder, frame, ".exr")) << folder << frame;
        EXPECT_EQ(file("whole", "occlusion", frame, ".png"), file("sync", "occlusion", frame, ".png")) << frame;
        for (const char* folder : {"right", "depth_right", "normal_right", "disparity_right"})
            EXPECT_EQ(file("whole", folder, frame, ".exr"), file("sync", folder, frame + 1, ".exr")) << folder << frame;
        EXPECT_EQ(file("whole", "occlusion_right", frame, ".png"), file("sync", "occlusion_right", frame + 1, ".png"))
            << frame;
        // The test can fail: the right camera moved over the offset.
        EXPECT_NE(file("whole", "depth_right", frame, ".exr"), file("sync", "depth_right", frame, ".exr")) << frame;
    }
    // stereo_offset_s 0: a synchronised rig, the very files of a sensor without the key.
    const std::string zero = write("zero", {{"stereo_offset_s", 0.0}});
    ASSERT_EQ(sward::test::runSwardRender(zero + " --out " + dir + "/zero --frames 0:2", err), 0) << err;
    EXPECT_GE(sward::test::expectSameRunFiles(dir + "/zero", dir + "/sync"), 2u * 18);
}

// frames.jsonl: the right camera's time and its pose then, its exposure's sub-frames and, with a rolling shutter, its
// first and last rows' times and poses (of its own readout, around its time); the left's stay the frame's.
TEST(StereoOffset, FramesRecordEachCamerasTimeAndPoses) {
    const SceneResources r = movingRig(
        {{"stereo_offset_s", kOffset}, {"readout_s", 0.05}, {"readout_bands", 4}, {"shutter_s", 0.01}}, false);
    const double t = kFrame * kStep;
    const nlohmann::json record =
        sequenceFrameRecord(r, sequenceRig(r, kW, kH, kFrame), kW, kH, kFrame, 0.0, std::span<const Collider>());
    auto pose = [&](double time, bool right) {
        const RigCameras rig = sequenceRigAt(r, kW, kH, time);
        return cameraPoseJson(right ? rig.right : rig.left);
    };
    EXPECT_EQ(record["time"], t);
    EXPECT_EQ(record["right_time"], t + kOffset);
    EXPECT_EQ(record["left_pose"], pose(t, false));
    EXPECT_EQ(record["right_pose"], pose(t + kOffset, true));
    EXPECT_NE(record["right_pose"], pose(t, true));
    EXPECT_EQ(record["right_exposure"]["times"],
              nlohmann::json(exposureTimesAt(r, r.scene.camera.rig.sensor, kW, kH, t + kOffset)));
    const std::vector<ReadoutBand> left = readoutBands(t, 0.05, kH, 4), right = readoutBands(t + kOffset, 0.05, kH, 4);
    EXPECT_EQ(record["readout"]["first_row"]["time"], left.front().time);
    EXPECT_EQ(record["readout"]["last_row"]["right_time"], right.back().time);
    EXPECT_EQ(record["readout"]["first_row"]["right_pose"], pose(right.front().time, true));
    EXPECT_EQ(record["readout"]["last_row"]["left_pose"], pose(left.back().time, false));
}

// The key: parsed within [-1, 1] s, written back for frames.jsonl (absent when 0, so a synchronised rig's records
// stay as they were), refused with one error on a single camera.
TEST(StereoOffset, KeyIsCheckedAndWrittenBack) {
    const SensorParams p = parseSensor({{"stereo_offset_s", -0.004}}, "scene.json", "camera.sensor");
    EXPECT_EQ(p.stereoOffsetSeconds, -0.004);
    EXPECT_EQ(sensorToJson(p)["stereo_offset_s"], -0.004);
    EXPECT_FALSE(sensorToJson(parseSensor({{"stereo_offset_s", 0}}, "s", "camera.sensor")).contains("stereo_offset_s"));
    auto error = [](const std::string& json) {
        try {
            parseScene(nlohmann::json::parse(json), "scene.json");
        } catch (const std::exception& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(error(R"({"camera": {"sensor": {"stereo_offset_s": 1.5}, "baseline": 0.1}})"),
              "scene.json: 'camera.sensor.stereo_offset_s' must be between -1 and 1 (got 1.5)");
    EXPECT_EQ(error(R"({"camera": {"sensor": {"stereo_offset_s": 0.01}, "baseline": 0}})"),
              "scene.json: 'camera.sensor.stereo_offset_s' needs a stereo rig ('camera.baseline' > 0): a single "
              "camera has no right view to offset");
    EXPECT_EQ(error(R"({"camera": {"sensor": {"stereo_offset_s": 0.01}, "baseline": 0.1}})"), "no error");
}

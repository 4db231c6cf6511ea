#include "render/sequence_frame.h"

#include "render/auto_exposure.h"
#include "render/motion_blur.h"
#include "render/rolling_shutter.h"
#include "render/track_renderer.h"

#include "common/error.h"
#include "dataset/frame_record.h"
#include "scene/world_objects.h"

#include <functional>

namespace sward {

void overrideCamera(Scene& scene, const std::optional<glm::dvec3>& position, const std::optional<glm::dvec3>& lookAt,
                    const std::optional<double>& fovYDegrees) {
    if (position) {
        scene.camera.position = *position;
        scene.camera.useHeightAboveGround = false;
        scene.camera.hasPath = false;
        scene.camera.rig.mountObject.clear();
    }
    if (lookAt) { // the scene's position unless a position is given too
        scene.camera.lookAt = *lookAt;
        scene.camera.lookAtUsesGround = false;
        scene.camera.hasPath = false;
        scene.camera.rig.mountObject.clear();
    }
    if (fovYDegrees) {
        require(*fovYDegrees >= 1.0 && *fovYDegrees <= 170.0, "--fov must be between 1 and 170 degrees");
        scene.camera.fovYDegrees = *fovYDegrees;
    }
}

RigCameras sequenceRig(const SceneResources& r, uint32_t width, uint32_t height, uint32_t frame) {
    return sequenceRigAt(r, width, height, double(frame) * r.scene.sequence.timeStep);
}

RigCameras sequenceRigAt(const SceneResources& r, uint32_t width, uint32_t height, double time) {
    if (r.world) return worldRig(r.scene, r.models, width, height, time);
    return sceneRig(r.scene, r.terrain, r.models, width, height, time);
}

nlohmann::json sequenceFrameRecord(const SceneResources& r, const RigCameras& rig, uint32_t width, uint32_t height,
                                   uint32_t frame, double timeOffset, std::span<const Collider> acting) {
    nlohmann::json record = frameRecord(r.scene, r.models, r.terrain, rig, frame, timeOffset, acting);
    // A world's range sensors stand on its lattice ground around their sweeps, as they cast (range/range_sweep.h).
    for (size_t k = 0; r.world && k < r.scene.rangeSensors.size(); ++k) {
        const RangeSensorParams& s = r.scene.rangeSensors[k];
        const double start = double(frame) * r.scene.sequence.timeStep, end = start + columnTime(s, s.columns() - 1);
        const Ground ground = sweepGround(r.scene, r.models, s, start);
        record["range_sensors"][k]["start_pose"] = matrixJson(rangeSensorPose(r.scene, s, ground, r.models, start));
        record["range_sensors"][k]["end_pose"] = matrixJson(rangeSensorPose(r.scene, s, ground, r.models, end));
    }
    // A world's objects stand on their own lattice ground, as they are drawn (scene/world_objects.h).
    for (size_t k = 0; r.world && k < r.scene.objects.size() && k < r.models.size(); ++k) {
        const double time = double(frame) * r.scene.sequence.timeStep;
        const Ground ground = objectGround(r.scene, r.scene.objects[k], r.models[k], time);
        const ObjectPose pose = objectPose(r.scene.objects[k], r.models[k], ground, time);
        record["objects"][k]["pose"] = matrixJson(pose.worldFromModel);
    }
    // A shutter's sub-frames (render/motion_blur.h): their count ("auto" follows the motion) and times.
    const SensorParams& sensor = r.scene.camera.rig.sensor;
    const std::vector<double> exposure = frameExposureTimes(r, sensor, width, height, frame);
    if (!exposure.empty()) record["exposure"] = {{"samples", exposure.size()}, {"times", exposure}};
    // An unsynchronised rig: the right camera's time, its pose then and its exposure's sub-frame times.
    if (sensor.enabled && sensor.stereoOffsetSeconds != 0.0) {
        const double rightTime = double(frame) * r.scene.sequence.timeStep + sensor.stereoOffsetSeconds;
        record["right_time"] = rightTime;
        record["right_pose"] = cameraPoseJson(sequenceRigAt(r, width, height, rightTime).right);
        const std::vector<double> right = exposureTimesAt(r, sensor, width, height, rightTime);
        if (!right.empty()) record["right_exposure"] = {{"samples", right.size()}, {"times", right}};
    }
    // A rolling shutter's readout (render/rolling_shutter.h): the first and last rows' times and poses.
    if (nlohmann::json readout = readoutRecord(r, sensor, width, height, frame); !readout.is_null())
        record["readout"] = std::move(readout);
    return record;
}

std::optional<SensorModel> checkRigAndSensor(const SceneResources& r, uint32_t width, uint32_t height, uint32_t frame,
                                             RigCameras& rig) {
    try {
        rig = sequenceRig(r, width, height, frame);
    } catch (const Error& e) {
        throw Error(r.scene.source + ": 'camera.mount': " + e.what());
    }
    std::optional<SensorModel> sensor;
    // A rolling shutter's bands after the first render their truth after the flow's next tick has run, so with plants
    // that colliders press the motion truth of those rows would see the next tick's plants (untested, and a run must
    // never write a wrong dataset): refused until the kept states are replayed per band.
    const SensorParams& params = r.scene.camera.rig.sensor;
    require(!(params.enabled && params.readoutSeconds > 0.0 && r.scene.render.flow && sceneHasColliders(r.scene)),
            r.scene.source +
                ": 'camera.sensor.readout_s' with 'render.flow' in a scene whose colliders press the "
                "plants is not supported yet: use a global shutter (readout_s 0) or turn 'render.flow' off");
    // So with an unsynchronised rig: its right view renders before the flow's next tick, whose kept plant states its
    // motion truth would read, where a synchronised render's reads those kept just before that tick.
    require(!(params.enabled && params.stereoOffsetSeconds != 0.0 && r.scene.render.flow && sceneHasColliders(r.scene)),
            r.scene.source + ": 'camera.sensor.stereo_offset_s' with 'render.flow' in a scene whose colliders press "
                             "the plants is not supported yet: use a synchronised rig (stereo_offset_s 0) or turn "
                             "'render.flow' off");
    if (r.scene.camera.rig.sensor.enabled) {
        try {
            sensor.emplace(r.scene.camera.rig.sensor, Intrinsics::of(rig.left));
        } catch (const Error& e) {
            throw Error(r.scene.source + ": 'camera.sensor': " + e.what());
        }
    }
    return sensor;
}

namespace {

// The interaction tick of a frame with motion ground truth: the plants' state of the previous tick is kept before the
// tick runs (VegetationRenderer::recordKeepState). Without a simulation the plants' records never change: the kept
// states enableFlow() made stay right.
void recordFlowTick(SceneGpu& gpu, VkCommandBuffer cmd, uint32_t tick) {
    if (!gpu.simulation && !gpu.worldSimulation) return;
    if (VegetationRenderer* plants = gpu.renderer->vegetation()) plants->recordKeepState(cmd);
    if (gpu.worldSimulation)
        gpu.worldSimulation->recordNextTick(cmd, tick); // prepared by prepareWorldFlowTicks
    else
        gpu.simulation->recordNextTick(cmd, tick);
}

// The prologue of a frame with motion ground truth: this frame's tick, unless the previous frame ran it before its
// truth passes (or prepareWorldFlowTicks before the frame).
std::function<void(VkCommandBuffer)> flowPrologue(SceneGpu& gpu, uint32_t frame) {
    if (VegetationRenderer* plants = gpu.renderer->vegetation()) plants->enableFlow();
    if (gpu.worldSimulation || (gpu.simulation && gpu.simulation->nextTick() == uint64_t(frame) + 1)) return {};
    return [&gpu, frame](VkCommandBuffer cmd) { recordFlowTick(gpu, cmd, frame); };
}

// A world's simulation with motion ground truth. As on one tile, the next tick (f + 1) runs between the frame's main
// and truth passes, its state kept first; but a world's tick is prepared outside any command buffer, and preparing
// tick f + 1 changes what is resident, so tick f runs before the frame, in a submission of its own (the state before
// it kept first), unless the previous frame's truth ran it; then tick f + 1 is prepared. Residency at t - 1, t, t + 1:
// that prepare keeps every tile within load_radius of this frame's cameras (`around`) resident, so every tile the
// frame draws has its kept state of tick f - 1 and gets tick f + 1; a tile it makes resident lies beyond them and was
// not resident at tick f, which left it unchanged: its kept states, its live records, are its state at f - 1 and f.
// An evicted tile's plants have recovered (WorldTiles), so tick f + 1 would not move them.
void prepareWorldFlowTicks(SceneGpu& gpu, uint32_t frame, std::span<const glm::dvec2> around) {
    WorldSimulation& sim = *gpu.worldSimulation;
    VegetationRenderer& plants = *gpu.renderer->vegetation(); // a world simulation needs drawn plants
    plants.enableFlow();
    if (sim.nextTick() != uint64_t(frame) + 1) {
        sim.runTicksBefore(frame);
        require(sim.nextTick() == frame,
                "frame " + std::to_string(frame) + " cannot be rendered: the world's simulation is at tick " +
                    std::to_string(sim.nextTick()) + " and never goes back (restore a saved state)");
        sim.runNextTick(around, [&](VkCommandBuffer cmd) { plants.recordKeepState(cmd); });
    }
    sim.prepare(around);
}

// renderSequenceFrame with the motion ground truth (render.flow). This tick's plant
// state is kept before the next tick runs between the main and the truth passes. `rowTime` (a rolling shutter's band,
// render/rolling_shutter.h, or an unsynchronised rig's right camera's time): the flow's rigs are those a step before
// and after that time, and the next tick is recorded only with `tickNext` (the first band's truth: the later bands'
// find it run).
FrameImages renderFlowFrame(SceneGpu& gpu, OffscreenFrame& target, const SceneResources& r, uint32_t frame, double time,
                            const RigCameras& cameras, const std::function<void(VkCommandBuffer)>& prologue,
                            bool colour, std::optional<double> rowTime = {}, bool tickNext = true,
                            const std::function<void()>& beforeNextTick = {}) {
    const uint32_t width = cameras.left.width, height = cameras.left.height;
    const double step = r.scene.sequence.timeStep;
    const RigCameras previous = rowTime ? sequenceRigAt(r, width, height, frame > 0 ? *rowTime - step : *rowTime)
                                        : sequenceRig(r, width, height, frame > 0 ? frame - 1 : 0); // frame 0: none
    const RigCameras next =
        rowTime ? sequenceRigAt(r, width, height, *rowTime + step) : sequenceRig(r, width, height, frame + 1);
    const bool stereo = r.scene.camera.rig.stereo();
    FlowTicks flow{.previous = {&previous.left, &previous.right},
                   .next = {&next.left, &next.right},
                   .timeStep = r.scene.sequence.timeStep,
                   .beforeTruth = [&](VkCommandBuffer cmd) {
                       if (beforeNextTick) beforeNextTick(); // the CPU state of tick f, before f + 1 changes it
                       recordFlowTick(gpu, cmd, frame + 1);
                   }};
    if (!tickNext) flow.beforeTruth = {};
    return target.render(*gpu.renderer, cameras.left, time, frame, prologue, stereo ? &cameras.right : nullptr, &flow,
                         colour);
}

// The sensor's read-out of a frame's light: the lens, then the sensor model (noise keyed by seed, frame, camera).
FrameImages readOutSensor(const SceneResources& r, const SensorModel& sensor, const RigCameras& cameras, uint32_t frame,
                          FrameImages images, AutoExposure* autoExposure) {
    double scale = 1.0; // auto-exposure meters the light before the lens (render/auto_exposure.h)
    if (autoExposure) scale = (images.autoExposure = autoExposure->meter(frame, images.rgbaHalf))->factor;
    // The lens before the sensor, each view defocused by its own exact depth (the rig is rectified: one fx, cx).
    const SensorOptics optics(sensor.params(), Intrinsics::of(cameras.left));
    optics.applyHalf(images.depth, images.rgbaHalf);
    if (!images.rightRgbaHalf.empty()) optics.applyHalf(images.rightDepth, images.rightRgbaHalf);
    sensor.applyHalf(r.scene.seed, frame, 0, images.rgbaHalf, scale, &images.raw); // raw: with a bit depth
    if (!images.rightRgbaHalf.empty())
        sensor.applyHalf(r.scene.seed, frame, 1, images.rightRgbaHalf, scale, &images.rightRaw);
    return images;
}

// A rolling shutter's frame (render/rolling_shutter.h) read out around `time`: every band's colour (its exposure of
// `exposureSamples` sub-frames, or its instant), `tick` before the first, then every band's truth at the band's time
// (the flow's next tick with the first, if `tickNext`), the rows of each copied out. With a shutter each band's
// motion_blur is its exposure's.
FrameImages renderReadout(SceneGpu& gpu, OffscreenFrame& target, const SceneResources& r, uint32_t width,
                          uint32_t height, uint32_t frame, double time, double timeOffset, const SensorParams& sensor,
                          size_t exposureSamples, const std::function<void(VkCommandBuffer)>& tick, bool tickNext,
                          const std::function<void()>& beforeNextTick) {
    const bool stereo = r.scene.camera.rig.stereo();
    const double half = 0.5 * sensor.shutterSeconds;
    auto rigAt = [&](double t) { return sequenceRigAt(r, width, height, t); };
    auto colourAt = [&](double t, bool first) {
        return renderBandColour(*gpu.renderer, target, rigAt, stereo, t, sensor.shutterSeconds,
                                uint32_t(exposureSamples), timeOffset, frame,
                                first ? tick : std::function<void(VkCommandBuffer)>());
    };
    auto truthAt = [&](double t, bool first) {
        const RigCameras rig = rigAt(t);
        FrameImages images = target.hasFlow() ? renderFlowFrame(gpu, target, r, frame, timeOffset + t, rig, {}, false,
                                                                t, first && tickNext, beforeNextTick)
                                              : target.render(*gpu.renderer, rig.left, timeOffset + t, frame, {},
                                                              stereo ? &rig.right : nullptr, nullptr, false);
        if (exposureSamples > 0)
            images.motionBlur = motionBlurLengths(rigAt(t - half).left, rig.left, rigAt(t + half).left, images.depth);
        return images;
    };
    return composeReadout(readoutBands(time, sensor.readoutSeconds, height, sensor.readoutBands), width, height,
                          colourAt, truthAt);
}

// The light of the rig's views at `time` (the frame's, or an unsynchronised rig's right camera's), before the lens and
// the sensor read it out: a rolling shutter's bands, a shutter's exposure (the truth at `time`, its middle) or the
// instant. `tick` (the frame's) goes before the first render; the flow's next tick before the truth only with
// `tickNext`. `flowTime`: the flow's rigs are a step before and after it, not the neighbouring frames'.
FrameImages renderLight(SceneGpu& gpu, OffscreenFrame& target, const SceneResources& r, uint32_t width, uint32_t height,
                        uint32_t frame, double time, std::optional<double> flowTime, double timeOffset,
                        const SensorParams* sensor, std::function<void(VkCommandBuffer)> tick, bool tickNext,
                        const std::function<void()>& beforeNextTick) {
    const bool stereo = r.scene.camera.rig.stereo();
    auto rigAt = [&](double t) { return sequenceRigAt(r, width, height, t); };
    // A shutter's sub-frame times (render/motion_blur.h); none: the colour is the instant's.
    const std::vector<double> exposure =
        sensor ? exposureTimesAt(r, *sensor, width, height, time) : std::vector<double>();
    if (sensor && sensor->readoutSeconds > 0.0) // a rolling shutter: each band of rows at its own time
        return renderReadout(gpu, target, r, width, height, frame, time, timeOffset, *sensor, exposure.size(), tick,
                             tickNext, beforeNextTick);
    ExposureColour blurred;
    if (!exposure.empty()) { // the frame's tick runs before the first sub-frame, and only then
        blurred = renderExposure(*gpu.renderer, target, rigAt, stereo, exposure, timeOffset, frame, tick);
        tick = {};
    }
    const bool colour = exposure.empty(); // else the truth alone, at the exposure's middle
    const RigCameras cameras = rigAt(time);
    FrameImages images = target.hasFlow() ? renderFlowFrame(gpu, target, r, frame, timeOffset + time, cameras, tick,
                                                            colour, flowTime, tickNext, beforeNextTick)
                                          : target.render(*gpu.renderer, cameras.left, timeOffset + time, frame, tick,
                                                          stereo ? &cameras.right : nullptr, nullptr, colour);
    if (!colour) {
        images.rgbaHalf = std::move(blurred.left);
        images.rightRgbaHalf = std::move(blurred.right);
        const double half = 0.5 * sensor->shutterSeconds;
        images.motionBlur =
            motionBlurLengths(rigAt(time - half).left, cameras.left, rigAt(time + half).left, images.depth);
    }
    return images;
}

// An unsynchronised rig's frame: the left view of the render at the frame's time (`left`) and the right view of the
// render at the right camera's (`right`). The other view of each, the rig's at that instant, is kept for the
// occlusion masks (FrameImages::rightDepthAtLeftTime, leftDepthAtRightTime).
FrameImages unsynchronisedViews(FrameImages left, FrameImages right) {
    left.rightDepthAtLeftTime = std::move(left.rightDepth);
    left.leftDepthAtRightTime = std::move(right.depth);
    left.rightRgbaHalf = std::move(right.rightRgbaHalf);
    left.rightDepth = std::move(right.rightDepth);
    left.rightLabels = std::move(right.rightLabels);
    left.rightNormals = std::move(right.rightNormals);
    left.rightFlowForward = std::move(right.rightFlowForward);
    left.rightFlowBackward = std::move(right.rightFlowBackward);
    return left;
}

// The points around which a world keeps its tiles resident for the rig at `time`: the left camera then, at its
// exposure's sub-frames and at a rolling shutter's first and last rows' exposures.
void addWorldCameras(const SceneResources& r, uint32_t width, uint32_t height, double time,
                     const std::optional<SensorModel>& sensor, std::vector<glm::dvec2>& around) {
    auto rigAt = [&](double t) { return sequenceRigAt(r, width, height, t); };
    around.push_back(glm::dvec2(rigAt(time).left.position));
    if (!sensor) return;
    for (double t : exposureTimesAt(r, sensor->params(), width, height, time))
        around.push_back(glm::dvec2(rigAt(t).left.position));
    const double readout = sensor->params().readoutSeconds, shutter = sensor->params().shutterSeconds;
    if (readout > 0.0)
        for (double t : {time - 0.5 * readout, time + 0.5 * readout})
            for (double s : {-0.5, 0.5}) around.push_back(glm::dvec2(rigAt(t + s * shutter).left.position));
}

} // namespace

FrameImages renderSequenceFrame(SceneGpu& gpu, OffscreenFrame& target, const SceneResources& r, uint32_t width,
                                uint32_t height, uint32_t frame, double timeOffset,
                                const std::optional<SensorModel>& sensor, RigCameras& cameras,
                                AutoExposure* autoExposure, const std::function<void()>& beforeNextTick) {
    const double time = double(frame) * r.scene.sequence.timeStep;
    cameras = sequenceRig(r, width, height, frame);
    const SensorParams* params = sensor ? &sensor->params() : nullptr;
    // An unsynchronised rig: the right camera's exposure and readout are centred on its own time.
    const double offset = params ? params->stereoOffsetSeconds : 0.0;
    std::function<void(VkCommandBuffer)> tick;
    std::vector<glm::dvec2> around; // a world's cameras: every tile within load_radius of them is drawn
    if (r.world) {
        addWorldCameras(r, width, height, time, sensor, around);
        // The range sensors' sweeps start within load_radius of the tiles their rays meet (range/range_recorder.h).
        for (const glm::dvec2& start : rangeSensorStarts(r.scene, r.models, time)) around.push_back(start);
        if (offset != 0.0) addWorldCameras(r, width, height, time + offset, sensor, around);
    }
    if (gpu.worldSimulation && target.hasFlow()) {
        prepareWorldFlowTicks(gpu, frame, around);
    } else if (gpu.worldSimulation) { // the tiles around the cameras and the actors, generated before the frame
        gpu.worldSimulation->runTicksBefore(frame);
        require(gpu.worldSimulation->nextTick() == frame,
                "frame " + std::to_string(frame) + " cannot be rendered: the world's simulation is at tick " +
                    std::to_string(gpu.worldSimulation->nextTick()) + " and never goes back (restore a saved state)");
        gpu.worldSimulation->prepare(around);
        tick = [&](VkCommandBuffer cmd) { gpu.worldSimulation->recordNextTick(cmd, frame); };
    } else if (r.world) { // generated before the frame: deterministic
        r.world->waitFor(around);
        syncWorldTiles(*gpu.renderer, *r.world);
    }
    if (gpu.simulation) {
        gpu.simulation->runTicksBefore(frame); // ticks of frames skipped or rendered elsewhere (shards)
        tick = [&](VkCommandBuffer cmd) { gpu.simulation->recordNextTick(cmd, frame); };
    }
    if (target.hasFlow()) tick = flowPrologue(gpu, frame);
    FrameImages images;
    if (offset == 0.0) {
        images =
            renderLight(gpu, target, r, width, height, frame, time, {}, timeOffset, params, tick, true, beforeNextTick);
    } else {
        // An unsynchronised rig: the whole rig rendered at the right camera's time, its right view kept, then at the
        // frame's time, its left view kept. The right goes first with the frame's tick, so both see that tick's
        // plants (as a shutter's sub-frames and a readout's bands do); the left's truth then runs the flow's next tick.
        const double rightTime = time + offset;
        FrameImages right = renderLight(gpu, target, r, width, height, frame, rightTime, rightTime, timeOffset, params,
                                        tick, false, {});
        images = unsynchronisedViews(
            renderLight(gpu, target, r, width, height, frame, time, {}, timeOffset, params, {}, true, beforeNextTick),
            std::move(right));
        cameras.right = sequenceRigAt(r, width, height, rightTime).right;
    }
    // After the exposure's mean: light is integrated first, then the sensor reads it out.
    return sensor ? readOutSensor(r, *sensor, cameras, frame, std::move(images), autoExposure) : images;
}

RangeFrameState rangeFrameState(SceneGpu& gpu, const SceneResources& r, RutPatchCache& ruts) {
    RangeFrameState state;
    if (!gpu.simulation && !gpu.worldSimulation) return state;
    // A world's CPU tiles hold the plants' state the range sensors see, once read back.
    if (gpu.worldSimulation) gpu.worldSimulation->readBackTiles();
    if (gpu.simulation && gpu.simulation->hasPlants()) state.dynamics = gpu.simulation->gpu().readDynamics();
    state.patches = rangeRutPatches(gpu, r, ruts);
    return state;
}

// The plants' state kept before the next tick: VegetationRenderer::recordKeepState copied the live records of tick f
// there, in the frame's command buffer, just before tick f + 1 (render.flow keeps it for the truth's backward flow).
RangeFrameState rangeFlowFrameState(SceneGpu& gpu, std::shared_ptr<const std::vector<GroundPatch>> patches) {
    RangeFrameState state;
    if (!gpu.simulation && !gpu.worldSimulation) return state; // no tick moves a plant
    if (gpu.worldSimulation && gpu.renderer->vegetation()) gpu.worldSimulation->readBackKeptStates();
    if (gpu.simulation && gpu.simulation->hasPlants()) state.dynamics = gpu.renderer->vegetation()->readKeptState();
    state.patches = std::move(patches);
    return state;
}

std::shared_ptr<const std::vector<GroundPatch>> rangeRutPatches(SceneGpu& gpu, const SceneResources& r,
                                                                RutPatchCache& ruts) {
    if (!gpu.simulation && !gpu.worldSimulation) return nullptr;
    // A world's ruts lie on the world's lattice ground (worldTrackPatchVertices).
    const GroundTracks& tracks = gpu.worldSimulation ? gpu.worldSimulation->tracks() : gpu.simulation->tracks();
    if (tracks.revision() != ruts.revision) {
        if (!r.world && !ruts.mesh && !tracks.blocks().empty()) ruts.mesh = groundDrawMesh(r.terrain);
        auto patches = std::make_shared<std::vector<GroundPatch>>();
        for (const auto& [key, depths] : tracks.blocks()) {
            GroundPatch patch{key.x, key.y, {}};
            for (const gpu::TerrainVertex& v : r.world ? worldTrackPatchVertices(tracks, r.scene, key)
                                                       : trackPatchVertices(tracks, r.terrain, *ruts.mesh, key))
                patch.points.push_back(v.positionHeight);
            patches->push_back(std::move(patch));
        }
        ruts.patches = patches->empty() ? nullptr : std::move(patches);
        ruts.revision = tracks.revision();
    }
    return ruts.patches;
}

} // namespace sward

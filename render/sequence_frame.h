// One frame of a scene's sequence as sward-render renders it — the rig at the frame's time, the interaction ticks up
// to and including the frame's own, the render and the sensor model — shared by the render job and the Python
// module (render/session.h), so a frame rendered either way is bitwise the same.
#pragma once

#include "range/range_recorder.h"
#include "render/ground_mesh.h"
#include "render/scene_gpu.h"
#include "scene/camera_rig.h"
#include "scene/sensor_model.h"

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <span>

namespace sward {

class AutoExposure;

// A fixed camera instead of the scene's (--camera, --look-at, --fov; the Python module's set_camera): a position
// or a target given here is absolute and detaches the rig from its path and mount. Checks the field of view.
void overrideCamera(Scene& scene, const std::optional<glm::dvec3>& position, const std::optional<glm::dvec3>& lookAt,
                    const std::optional<double>& fovYDegrees);

// The rig of frame `frame` (time frame * sequence.time_step) for width x height images.
RigCameras sequenceRig(const SceneResources& r, uint32_t width, uint32_t height, uint32_t frame);
// The rig at any simulation time (an exposure's sub-frames, render/motion_blur.h); sequenceRig at frame * time_step.
RigCameras sequenceRigAt(const SceneResources& r, uint32_t width, uint32_t height, double time);

// The rig of `frame` (which checks a mount) and the scene's sensor model (which checks its lens is invertible over
// the image), each error naming the scene and the key; call before anything is written.
std::optional<SensorModel> checkRigAndSensor(const SceneResources& r, uint32_t width, uint32_t height, uint32_t frame,
                                             RigCameras& rig);

// Frame `frame`'s frames.jsonl record (dataset/frame_record.h) for the rig `rig` and the colliders `acting` during its
// tick, with a shutter's sub-frame times ("exposure") and a rolling shutter's readout: what sward-render writes for a
// sequence and the episode recorder (render/episode_recorder.h) for a frame a program drove.
nlohmann::json sequenceFrameRecord(const SceneResources& r, const RigCameras& rig, uint32_t width, uint32_t height,
                                   uint32_t frame, double timeOffset, std::span<const Collider> acting);

// Renders `frame` (width x height: `target`'s size): first simulates the ticks before it that have not run (each its own submission), then records
// the frame's own tick, the views and the readbacks in one submission; applies the sensor model with the (seed,
// frame, camera) noise key. `timeOffset` is added to the wind's time (--time). Returns the rig in `cameras`.
// A `target` made with flow (render.flow) also gets the motion ground truth: the frame's tick runs unless the previous
// frame's already ran it, and the next tick runs before the truth passes (FlowTicks), so the simulation ends one tick
// ahead; frames must then come in increasing order. `autoExposure` (camera.sensor.auto_exposure): meters the frame and
// applies the exposure of its window (render/auto_exposure.h), recorded in FrameImages::autoExposure.
// `beforeNextTick` (flow only): called while the frame is recorded, once its own tick has run and before the next
// tick's is recorded: the CPU state of the frame's tick (the range sensors' rut patches, rangeFlowFrameState).
FrameImages renderSequenceFrame(SceneGpu& gpu, OffscreenFrame& target, const SceneResources& r, uint32_t width,
                                uint32_t height, uint32_t frame, double timeOffset,
                                const std::optional<SensorModel>& sensor, RigCameras& cameras,
                                AutoExposure* autoExposure = nullptr, const std::function<void()>& beforeNextTick = {});

// What the range sensors (range/range_recorder.h) see of a rendered frame besides the scene: the plants' interaction
// state (the GPU's dynamic records after the frame's tick) and the ground's rut patches as the track renderer draws
// them. The dynamic records are a copy (the next frame's ticks change them); the patches are shared, and replaced by a
// new vector when the ruts change.
struct RangeFrameState {
    std::vector<gpu::PlantDynamic> dynamics;
    std::shared_ptr<const std::vector<GroundPatch>> patches;
    RangeRecorder::FrameState view(double windTimeOffset) const { return {dynamics, patches, windTimeOffset}; }
};
// The rut patches of the latest revision of the ruts, rebuilt only when they change (null: no rut).
struct RutPatchCache {
    std::optional<GroundDrawMesh> mesh;
    uint64_t revision = ~uint64_t(0);
    std::shared_ptr<const std::vector<GroundPatch>> patches;
};
// The state of the frame `gpu` rendered last (reads the dynamic records back: waits for the GPU).
RangeFrameState rangeFrameState(SceneGpu& gpu, const SceneResources& r, RutPatchCache& ruts);
// The ruts as the range sensors see them now: the latest revision's patches (null: no rut).
std::shared_ptr<const std::vector<GroundPatch>> rangeRutPatches(SceneGpu& gpu, const SceneResources& r,
                                                                RutPatchCache& ruts);
// The same state for a frame rendered with flow (render.flow). Such a frame runs its next tick (f + 1) before its
// truth passes, so after it the live plant records and the ruts are those of tick f + 1, one tick later than its
// cameras drew. The sweep of frame f must see tick f, as without flow: the plants' state is read from the copy the flow
// kept just before tick f + 1 (VegetationRenderer::readKeptState; a world's simulated tiles take it into their CPU
// copies, WorldSimulation::readBackKeptStates), and the ruts are `patches`, taken by rangeRutPatches from
// renderSequenceFrame's beforeNextTick. So a dataset's range files are bitwise the same with flow on or off.
RangeFrameState rangeFlowFrameState(SceneGpu& gpu, std::shared_ptr<const std::vector<GroundPatch>> patches);

} // namespace sward

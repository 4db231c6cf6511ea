// Session: a scene driven from a program tick by tick — the engine behind the Python module (python/). It renders
// exactly what sward-render renders (render/sequence_frame.h): frame f shows the state after tick f, at time
// f * sequence.time_step, so a session's frame and the dataset file of the same scene and frame are bitwise equal.
// Between frames the program may move the camera, the scene's objects and colliders of its own, step without
// rendering, and save or restore the interaction state.
#pragma once

#include "engine/context.h"
#include "interaction/vehicle_controller.h"
#include "render/auto_exposure.h"
#include "render/sequence_frame.h"
#include "scene/scene_resources.h"

#include <nlohmann/json.hpp>

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

namespace sward {

struct SessionOptions {
    std::string device;        // Vulkan device name substring (else SWARD_DEVICE, else the automatic choice)
    bool validation = false;   // Vulkan validation (also SWARD_VALIDATION=1); messages are counted, see below
    bool vegetation = true;    // false: the same scene without vegetation (--no-vegetation)
    double time = 0.0;         // seconds added to every frame's wind time (--time)
};

// One rendered frame and the rig that saw it.
struct SessionFrame {
    uint32_t frame = 0;
    FrameImages images;
    RigCameras cameras;
    double baseline = 0.0; // metres; 0 for a mono rig
    std::vector<RangeScan> range; // the scene's range sensors' sweeps of the frame, in scene order (range/)
    // The frame's frames.jsonl line (sequenceFrameRecord): tick, time, poses, intrinsics, wind, the colliders that
    // acted during its tick (the program's too) and the objects' poses, as the episode recorder writes it.
    nlohmann::json record;
};

class Session {
public:
    // Builds the scene's resources (every input checked), then the device, the renderer and the simulation. The
    // resolution and samples are the scene's ("render.resolution", "render.samples").
    Session(Scene scene, const SessionOptions& options);
    ~Session();
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;

    // The next frame render() shows, = the next interaction tick.
    uint32_t frame() const { return next_; }
    // Advances `ticks` ticks without rendering (the interaction runs each of them). With auto-exposure the last W of
    // them are rendered for their meter (render/auto_exposure.h), so the next frame's exposure is sward-render's.
    void step(uint32_t ticks);
    // A new episode on the same device (the Python module's reset). With `scene` (another seed or overrides) that
    // scene, built and checked as the constructor builds it (on failure the session is as it was), on the device
    // (and output image, when size and samples agree) already open. Without, the scene as it was built — camera,
    // objects, wind, sun and sky as loaded, no program colliders, no driven vehicle — and a new interaction at rest
    // (frame 0, no ruts, every plant as generated), keeping every buffer; a world drops every tile, resident or evicted,
    // with its touched fields (WorldTiles::clear), generated again as the frames need them. Either way the frames that
    // follow are those of a new Session of that scene, bitwise. Refused while a frame observer (a recorder) is attached.
    void reset(std::optional<Scene> scene = std::nullopt);
    // Whether frames are metered for auto-exposure (then step renders the last W ticks it runs).
    bool autoExposed() const { return autoExposure_.has_value(); }
    // Renders the next frame with its own tick, as sward-render would, and advances by one.
    SessionFrame render();

    // A fixed camera from now on (scene/render/sequence_frame.h overrideCamera).
    void setCamera(const std::optional<glm::dvec3>& position, const std::optional<glm::dvec3>& lookAt,
                   const std::optional<double>& fovYDegrees);
    // Object k stands at world xy `position`, heading `headingDegrees` (from +x towards +y), on the terrain,
    // instead of following its path: drawn there and its node colliders act there from the next tick.
    void setObjectPose(size_t k, glm::dvec2 position, double headingDegrees);
    // Colliders of the program's own (scene/collider_params.h), acting from the next tick until replaced.
    void setColliders(std::vector<Collider> colliders);
    // Drives object k as a vehicle (interaction/vehicle_controller.h) by one tick of sequence.time_step: from its pose
    // at the next frame's time on the first call (path or set pose), then from the state the last call left; its
    // model, node colliders and a rig mounted on it follow from the next tick (setObjectPose). Returns the new state.
    VehicleState drive(size_t k, const VehicleCommand& command);
    // The scene's "wind", "sun" or "sky" (`key`) from the next frame on: the keys of `value` over the current values
    // (updateSceneSection), drawn and recorded in frames.jsonl's records.
    void setWeather(const std::string& key, const nlohmann::json& value);

    // Called with every frame render() returns, before it returns (the episode recorder, render/episode_recorder.h);
    // an empty function removes it. What it throws reaches render()'s caller.
    void setFrameObserver(std::function<void(const SessionFrame&)> observer) { observer_ = std::move(observer); }
    bool observed() const { return bool(observer_); }

    // The interaction state (SWARDST1, interaction/state_file.h): tick, field activity, every plant's dynamic
    // record. restoreState continues from the saved tick; next frame = that tick. Auto-exposure's window restarts
    // there (the frames before it are not metered again): its next W frames differ from sward-render's.
    void saveState(const std::string& path);
    void restoreState(const std::string& path);

    const SceneResources& resources() const { return resources_; }
    const Device& device() const { return ctx_->device; }
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }

private:
    Simulation& simulation(const char* what);
    // The GPU side of resources_ on ctx_ (the renderer, the simulation, the range sensors, the output image when its
    // size or samples changed) and the episode's start: frame 0, the scene as built remembered for reset().
    void createGpu();
    void restart(); // reset() without a scene
    // The colliders that acted during the latest tick, as frames.jsonl records them (none on bare ground).
    std::vector<Collider> lastTickColliders() const;

    SceneResources resources_;
    SessionOptions options_;
    uint32_t width_ = 0, height_ = 0;
    std::optional<SensorModel> sensor_;
    std::optional<AutoExposure> autoExposure_; // the meters of the frames rendered (camera.sensor.auto_exposure)
    std::unique_ptr<Context> ctx_;
    SceneGpu gpu_;
    std::unique_ptr<OffscreenFrame> target_;
    std::unique_ptr<RangeRecorder> range_; // the scene's range sensors, if any
    RutPatchCache ruts_;
    uint32_t next_ = 0;
    std::map<size_t, VehicleState> vehicles_; // the objects drive() moves, by index
    std::function<void(const SessionFrame&)> observer_;
    Scene initial_;           // the scene as built, for reset()
    glm::uvec3 targetSize_{}; // target_'s width, height and samples
};

} // namespace sward

#include "render/session.h"

#include "common/error.h"
#include "render/object_renderer.h"
#include "scene/world_objects.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sward {

Session::Session(Scene scene, const SessionOptions& options)
    : resources_(buildSceneResources(std::move(scene), options.vegetation)), options_(options),
      width_(resources_.scene.render.width), height_(resources_.scene.render.height) {
    require(std::isfinite(options.time) && options.time >= 0.0, "time must be a finite, non-negative number of seconds");
    RigCameras firstRig;
    sensor_ = checkRigAndSensor(resources_, width_, height_, 0, firstRig); // before a device exists
    if (sensor_ && sensor_->params().autoExposure.enabled)
        autoExposure_.emplace(sensor_->params().autoExposure, resources_.scene.sequence.timeStep);
    ctx_ = std::make_unique<Context>(
        DeviceOptions{.deviceFilter = options.device, .validation = options.validation || DeviceOptions{}.validation});
    createGpu();
}

void Session::createGpu() {
    // Always a simulation: colliders placed from the program may touch plants at any tick. A tick with no contact
    // and no active field records nothing, so frames are the same as sward-render's.
    initial_ = resources_.scene;
    if (!resources_.scene.rangeSensors.empty()) range_ = std::make_unique<RangeRecorder>(resources_); // needs the atlas
    gpu_ = createSceneGpu(*ctx_, resources_, resources_.scene.render.samples, SimulationMode::Always);
    // A world's interaction likewise, with or without actors of the scene. With none acting it simulates no tile and
    // loads around the cameras as a world without one does, so frames stay sward-render's.
    if (resources_.world && !gpu_.worldSimulation && resources_.withVegetation() && gpu_.renderer->vegetation())
        gpu_.worldSimulation = std::make_unique<WorldSimulation>(*ctx_, resources_, *gpu_.renderer);
    const glm::uvec3 size(width_, height_, resources_.scene.render.samples);
    if (!target_ || size != targetSize_) {
        target_.reset();
        target_ = std::make_unique<OffscreenFrame>(*ctx_, width_, height_, size.z);
        targetSize_ = size;
    }
    next_ = 0;
    vehicles_.clear();
    ruts_ = RutPatchCache{};
}

void Session::reset(std::optional<Scene> scene) {
    // A recorder's dataset is one episode of one scene: its frames would start again at 0, or come from another scene.
    require(!observed(), "reset: this simulator is recording; close the recorder first (one episode, one dataset)");
    if (!scene) return restart();
    // Built and checked before the old scene is let go, so a bad scene leaves the session as it was.
    SceneResources resources = buildSceneResources(std::move(*scene), options_.vegetation);
    const uint32_t width = resources.scene.render.width, height = resources.scene.render.height;
    RigCameras firstRig;
    std::optional<SensorModel> sensor = checkRigAndSensor(resources, width, height, 0, firstRig);
    range_.reset(); // the GPU objects read the old resources: gone before them
    gpu_.worldSimulation.reset();
    gpu_.simulation.reset();
    gpu_.renderer.reset();
    resources_ = std::move(resources);
    width_ = width, height_ = height;
    sensor_ = std::move(sensor);
    autoExposure_.reset();
    if (sensor_ && sensor_->params().autoExposure.enabled)
        autoExposure_.emplace(sensor_->params().autoExposure, resources_.scene.sequence.timeStep);
    createGpu();
}

void Session::restart() {
    resources_.scene = initial_;
    if (ObjectRenderer* objects = gpu_.renderer->objects()) objects->resetObjects(initial_.objects);
    gpu_.renderer->setWeather(initial_.wind, initial_.sun, initial_.sky);
    if (resources_.world) { // every tile, resident or evicted, dropped with its touched fields: generated again
        const bool simulated = gpu_.worldSimulation != nullptr;
        gpu_.worldSimulation.reset(); // its tiles' interaction and the ruts
        resources_.world->clear();
        syncWorldTiles(*gpu_.renderer, *resources_.world);
        if (simulated) gpu_.worldSimulation = std::make_unique<WorldSimulation>(*ctx_, resources_, *gpu_.renderer);
    }
    if (gpu_.simulation) { // a new interaction: tick 0, no ruts, the plants' records as generated
        const bool plants = gpu_.simulation->hasPlants();
        gpu_.simulation.reset();
        gpu_.simulation = std::make_unique<Simulation>(*ctx_, resources_.scene, resources_.terrain,
                                                       plants ? &*resources_.tile : nullptr,
                                                       plants ? &gpu_.renderer->vegetation()->buffers() : nullptr);
        gpu_.simulation->setObjectModels(&resources_.models);
        if (plants) gpu_.simulation->gpu().writeDynamics(gpu_.simulation->world().initialDynamics());
        gpu_.renderer->setGroundTracks(&gpu_.simulation->tracks(), &resources_.terrain);
    }
    if (autoExposure_) autoExposure_->clear();
    next_ = 0;
    vehicles_.clear();
    ruts_ = RutPatchCache{};
}

Session::~Session() {
    // The renderer and the simulation hold GPU objects of the context: destroyed first, then the device.
    target_.reset();
    gpu_.worldSimulation.reset(); // these use the renderer's buffers: first
    gpu_.simulation.reset();
    gpu_.renderer.reset();
    ctx_.reset();
}

void Session::step(uint32_t ticks) {
    require(uint64_t(next_) + ticks <= UINT32_MAX, "step: the frame number would pass 2^32 - 1");
    const uint32_t end = next_ + ticks;
    if (autoExposure_) { // the window's frames rendered (their own ticks) for the meter of the frame after them
        for (uint32_t frame = std::max(next_, end > autoExposure_->window() ? end - autoExposure_->window() : 0);
             frame < end; ++frame) {
            RigCameras cameras;
            renderSequenceFrame(gpu_, *target_, resources_, width_, height_, frame, options_.time, sensor_, cameras,
                                &*autoExposure_);
        }
    }
    next_ = end;
    if (gpu_.simulation) gpu_.simulation->runTicksBefore(next_);
    if (gpu_.worldSimulation) gpu_.worldSimulation->runTicksBefore(next_);
}

SessionFrame Session::render() {
    require(next_ < UINT32_MAX, "render: the frame number would pass 2^32 - 1");
    SessionFrame out{.frame = next_};
    out.images = renderSequenceFrame(gpu_, *target_, resources_, width_, height_, next_, options_.time, sensor_,
                                     out.cameras, autoExposure_ ? &*autoExposure_ : nullptr);
    out.baseline = resources_.scene.camera.rig.baseline;
    if (range_) out.range = range_->sweep(next_, rangeFrameState(gpu_, resources_, ruts_).view(options_.time));
    out.record =
        sequenceFrameRecord(resources_, out.cameras, width_, height_, next_, options_.time, lastTickColliders());
    ++next_;
    if (observer_) observer_(out);
    return out;
}

void Session::setCamera(const std::optional<glm::dvec3>& position, const std::optional<glm::dvec3>& lookAt,
                        const std::optional<double>& fovYDegrees) {
    Scene& scene = resources_.scene;
    const CameraParams before = scene.camera;
    overrideCamera(scene, position, lookAt, fovYDegrees);
    try {
        sequenceRig(resources_, width_, height_, next_); // a camera looking at itself fails here, not mid-frame
    } catch (const Error&) {
        scene.camera = before;
        throw;
    }
}

void Session::setObjectPose(size_t k, glm::dvec2 position, double headingDegrees) {
    ObjectRenderer* objects = gpu_.renderer->objects();
    require(objects && k < resources_.scene.objects.size(),
            "set_object_pose: no object " + std::to_string(k) + " (the scene has " +
                std::to_string(resources_.scene.objects.size()) + ")");
    require(std::isfinite(position.x) && std::isfinite(position.y) && std::isfinite(headingDegrees),
            "set_object_pose: the pose must be finite");
    objects->place(k, position, headingDegrees * std::numbers::pi / 180.0);
    vehicles_.erase(k); // drive() starts again from this pose
    // The same one-point path for the node colliders (sceneColliders reads the scene's objects).
    resources_.scene.objects[k].path.points = {position};
    resources_.scene.objects[k].yawDegrees = headingDegrees;
}

void Session::setColliders(std::vector<Collider> colliders) {
    if (resources_.world) {
        require(gpu_.worldSimulation != nullptr,
                "set_colliders: the scene has no vegetation to interact with (vegetation off or empty)");
        return gpu_.worldSimulation->setExternalColliders(std::move(colliders));
    }
    simulation("set_colliders").setExternalColliders(std::move(colliders));
}

VehicleState Session::drive(size_t k, const VehicleCommand& command) {
    const std::vector<ObjectParams>& objects = resources_.scene.objects;
    require(k < objects.size() && k < resources_.models.size(),
            "drive: no object " + std::to_string(k) + " to drive (the scene has " + std::to_string(objects.size()) +
                " object(s), its 'objects')");
    checkVehicleCommand(command);
    auto it = vehicles_.find(k);
    if (it == vehicles_.end()) { // from where the object stands at the next frame, facing where its model faces
        const double time = double(next_) * resources_.scene.sequence.timeStep;
        // In a world, the lattice ground the object is drawn on there (scene/world_objects.h).
        const Ground world =
            resources_.world ? objectGround(resources_.scene, objects[k], resources_.models[k], time) : Ground();
        const ObjectPose pose =
            objectPose(objects[k], resources_.models[k], resources_.world ? world : resources_.terrain, time);
        const double heading = headingDegreesOf(glm::dvec2(pose.forward)) + objects[k].yawDegrees;
        it = vehicles_.emplace(k, VehicleState{.position = glm::dvec2(pose.position), .headingDegrees = heading}).first;
    }
    const VehicleState next = stepVehicle(it->second, command, VehicleLimits{}, resources_.scene.sequence.timeStep);
    setObjectPose(k, next.position, next.headingDegrees); // which forgets the state: a pose set from outside resets it
    vehicles_[k] = next;
    return next;
}

void Session::setWeather(const std::string& key, const nlohmann::json& value) {
    Scene& scene = resources_.scene;
    updateSceneSection(scene, key, value, "set_" + key);
    gpu_.renderer->setWeather(scene.wind, scene.sun, scene.sky);
}

std::vector<Collider> Session::lastTickColliders() const {
    if (!resources_.withVegetation()) return {}; // as sward-render records bare ground: no plant to act on
    if (gpu_.simulation) return gpu_.simulation->lastColliders(); // the scene's and the program's
    if (gpu_.worldSimulation) return gpu_.worldSimulation->lastColliders();
    return sceneColliders(resources_, next_);
}

void Session::saveState(const std::string& path) {
    if (gpu_.worldSimulation) return gpu_.worldSimulation->saveState(path);
    simulation("save_state").saveState(path);
}

void Session::restoreState(const std::string& path) {
    if (autoExposure_) autoExposure_->clear(); // the frames before the saved tick were never metered here
    if (gpu_.worldSimulation) {
        const uint64_t tick = gpu_.worldSimulation->restoreState(path);
        require(tick < UINT32_MAX, "restore_state: the saved tick is beyond the last frame");
        next_ = uint32_t(tick);
        return;
    }
    Simulation& sim = simulation("restore_state");
    sim.restoreState(path);
    require(sim.nextTick() < UINT32_MAX, "restore_state: the saved tick is beyond the last frame");
    next_ = uint32_t(sim.nextTick());
}

Simulation& Session::simulation(const char* what) { // one tile's (a world's callers use gpu_.worldSimulation)
    require(gpu_.simulation != nullptr,
            std::string(what) + ": the scene has no vegetation to interact with (vegetation off or empty)");
    return *gpu_.simulation;
}

} // namespace sward

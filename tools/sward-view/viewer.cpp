#include "viewer.h"

#include "engine/barriers.h"
#include "engine/context.h"
#include "engine/render_target.h"
#include "engine/swapchain.h"
#include "engine/timestamps.h"
#include "fly_camera.h"
#include "input.h"
#include "present_pass.h"
#include "render/vegetation_renderer.h"
#include "rover_control.h"
#include "scene_state.h"
#include "screenshots.h"
#include "test_hooks.h"
#include "ui.h"
#include "window.h"
#include "world_drive.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <unistd.h>

#ifndef SWARD_SOURCE_DIR
#define SWARD_SOURCE_DIR "."
#endif

namespace sward {

namespace {

using Clock = std::chrono::steady_clock;

std::string defaultScenePath() {
    if (std::filesystem::exists("examples/meadow.json")) return "examples/meadow.json";
    return std::string(SWARD_SOURCE_DIR) + "/examples/meadow.json";
}

std::filesystem::file_time_type modificationTime(const std::string& path) {
    std::error_code ec;
    auto t = std::filesystem::last_write_time(path, ec);
    return ec ? std::filesystem::file_time_type{} : t;
}

// The viewer wires the window, the scene state, the cameras, the rover, the panel and the passes; each frame is
// run() -> handleInput -> applyPanel -> acquire -> renderFrame (recordFrame, present, writeCaptures).
class Viewer {
public:
    Viewer(const ViewerOptions& options, Window& window, Context& ctx);
    ~Viewer();
    void run();

private:
    // Scene lifetime.
    void rebuild(const Scene& scene, bool keepInteraction);
    void reload();
    void resetCameraAndRover();
    void spawnRover();
    WorldTiles* world() const { return state_->resources.world.get(); }
    const Ground& roverGround() const; // a world's lattice ground around the rover (WorldDrive), else the scene's
    float groundHeight(glm::dvec2 xy) const;
    void streamWorld(const Camera& camera);
    float canopyHeight() const;
    // Input and the panel's edits.
    void onKey(int key, int action, int mods);
    void handleInput(double dt);
    void applyPanel();
    void applyDensity();
    // One frame.
    double advanceClocks();
    void renderFrame(const SwapchainImage& image, double dt);
    void updatePanel();
    void tickSimulation(VkCommandBuffer cmd, GpuTimers& timers);
    Camera viewCamera(VkExtent2D extent) const;
    void buildOverlay(const Camera& camera);
    void ensureTargets(VkExtent2D extent);
    uint64_t recordFrame(const SwapchainImage& image, const Camera& camera, RenderTarget* truth, bool capture);
    void writeCaptures(uint64_t serial, bool keyShot, bool capture);
    void printSummary() const;
    uint32_t samples() const { return panel_.msaa ? 4u : 1u; }
    bool headless() const { return options_.frames > 0; }
    // The keyboard rover's vehicle index: after the scene's own vehicles, so their collider ids never clash.
    uint32_t roverIndex() const { return uint32_t(state_->resources.scene.actors.vehicles.size()); }

    ViewerOptions options_;
    std::string scenePath_;
    Window& window_;
    Context& ctx_;
    Swapchain swapchain_;
    PresentPass present_;
    Screenshots screenshots_;
    std::unique_ptr<Ui> ui_;
    std::unique_ptr<SceneState> state_;
    std::unique_ptr<RenderTarget> main_;
    std::unique_ptr<GpuTimers> timers_[gpu::kFramesInFlight];
    TestHooks hooks_;

    PanelState panel_;
    FlyCamera camera_;
    RoverControl rover_;
    mutable std::optional<WorldDrive> worldDrive_; // a world: the rover's ground and the tiles it reached
    bool driving_ = false;                         // camera follows the rover, arrow keys drive it
    FlyControls flyControls_;
    bool uiVisible_ = true;
    double tickClock_ = 0.0;
    uint64_t frame_ = 0, attempts_ = 0;
    bool screenshotPending_ = false, stepPending_ = false;
    std::filesystem::file_time_type sceneTime_{};
    Clock::time_point lastFrame_{}, lastReloadCheck_{};
    std::vector<float> frameTimes_; // milliseconds, the latest 120 frames
    uint32_t recreations_ = 0;
};

Viewer::Viewer(const ViewerOptions& options, Window& window, Context& ctx)
    : options_(options), scenePath_(options.scenePath.empty() ? defaultScenePath() : options.scenePath),
      window_(window), ctx_(ctx), swapchain_(ctx, ctx.device.surface(), window.framebufferExtent(), options.vsync),
      present_(ctx), screenshots_(ctx, options.screenshotDir), hooks_(options) {
    Scene scene = loadScene(scenePath_, std::nullopt, options_.allowAssets);
    sceneTime_ = modificationTime(scenePath_);
    uint32_t samples = options.samples.value_or(scene.render.samples);
    require(samples == 1 || samples == 4, "--samples must be 1 or 4 (got " + std::to_string(samples) + ")");
    panel_.msaa = samples == 4;
    panel_.wind = scene.wind;
    panel_.lod = scene.lod;
    panel_.density = scene.vegetation.densityMultiplier;
    panel_.device = ctx_.device.name();
    enableOverlays(panel_, options.overlays);
    uiVisible_ = options.showUi;
    for (auto& t : timers_) t = std::make_unique<GpuTimers>(ctx_.device, 16);

    // GLFW callbacks go in before ImGui's backend, which chains to them.
    glfwSetWindowUserPointer(window_.handle, this);
    glfwSetKeyCallback(window_.handle, [](GLFWwindow* w, int key, int, int action, int mods) {
        static_cast<Viewer*>(glfwGetWindowUserPointer(w))->onKey(key, action, mods);
    });
    // '?' is a character, not a key: where it is depends on the keyboard layout.
    glfwSetCharCallback(window_.handle, [](GLFWwindow* w, unsigned int codepoint) {
        auto* viewer = static_cast<Viewer*>(glfwGetWindowUserPointer(w));
        if (codepoint == '?' && !(viewer->ui_ && viewer->ui_->wantsKeyboard()))
            toggleKeysHelp(viewer->panel_, viewer->uiVisible_);
    });
    glfwSetScrollCallback(window_.handle, [](GLFWwindow* w, double, double y) {
        static_cast<Viewer*>(glfwGetWindowUserPointer(w))->flyControls_.addScroll(y);
    });
    ui_ = std::make_unique<Ui>(ctx_, window_.handle, swapchain_);

    rebuild(scene, false);
    resetCameraAndRover();
    if (options.camera) {
        glm::dvec3 target = options.lookAt.value_or(*options.camera + camera_.forward());
        camera_ = FlyCamera(*options.camera, target);
    }
    if (options.drive || options.autodrive != 0.0) spawnRover();
    // --autodrive with --camera: watch the rover from that camera instead of following it.
    driving_ = options.drive || (options.autodrive != 0.0 && !options.camera);
}

Viewer::~Viewer() {
    ctx_.submitter.waitIdle();
    vkQueueWaitIdle(ctx_.device.queue());
    ui_.reset();
    state_.reset();
    main_.reset();
    for (auto& t : timers_) t.reset();
}

void Viewer::rebuild(const Scene& sceneIn, bool keepInteraction) {
    Scene scene = sceneIn; // may be state_->resources.scene, which is about to go
    // Interaction state survives an MSAA change (same plants): read it back, rebuild, upload it again.
    std::string stateFile;
    if (keepInteraction && state_ && (state_->gpu.simulation || state_->gpu.worldSimulation)) {
        stateFile =
            (std::filesystem::temp_directory_path() / ("sward-view-" + std::to_string(getpid()) + ".state")).string();
        if (state_->gpu.simulation)
            state_->gpu.simulation->saveState(stateFile);
        else
            state_->gpu.worldSimulation->saveState(stateFile); // tiles, kept fields and ruts
    }
    ctx_.submitter.waitIdle();
    state_.reset();
    main_.reset();
    screenshots_.dropTruthTarget();
    // Kept interaction needs the very same plants; otherwise the panel's density applies.
    if (!keepInteraction) scene.vegetation.densityMultiplier = panel_.density;
    state_ = loadSceneState(ctx_, scene, samples());
    if (!stateFile.empty()) {
        if (state_->gpu.simulation) state_->gpu.simulation->restoreState(stateFile);
        if (state_->gpu.worldSimulation) state_->gpu.worldSimulation->restoreState(stateFile);
        std::filesystem::remove(stateFile);
    }
    state_->gpu.renderer->setMainPassOverlay([this](VkCommandBuffer cmd, const DescriptorBinding& frame) {
        state_->overlay->draw(cmd, frame, uint32_t(frame_));
    });
    panel_.scene = state_->resources.scene.name + " (" + scenePath_ + ")";
    panel_.fieldCount = state_->resources.tile ? state_->resources.tile->fields.size() : 0;
    worldDrive_.reset();
    if (world()) worldDrive_.emplace(state_->resources.scene);
    rover_.setVehicle(state_->resources.scene.actors.vehicles.empty() ? VehicleParams{}
                                                                      : state_->resources.scene.actors.vehicles[0]);
}

void Viewer::spawnRover() {
    if (world())
        rover_.spawn(camera_, worldDrive_->groundAhead(camera_));
    else
        rover_.spawn(camera_, state_->resources.terrain);
}

const Ground& Viewer::roverGround() const {
    return worldDrive_ ? worldDrive_->groundAround(rover_.position()) : state_->resources.terrain;
}

// The ground under xy: in a world, of the resident tile there (none yet: the camera is not held up).
float Viewer::groundHeight(glm::dvec2 xy) const {
    if (world()) return world()->height(xy).value_or(-INFINITY);
    return state_->resources.terrain.height(glm::vec2(xy));
}

// A world's tiles around the camera: requested from the generator thread and drawn once they are ready, so a frame
// never waits for a generation (only for the upload of a finished tile).
void Viewer::streamWorld(const Camera& camera) {
    if (!world()) return;
    std::vector<glm::dvec2> points{glm::dvec2(camera.position)};
    if (rover_.active()) points.push_back(rover_.position()); // its tiles come as it drives
    try {
        world()->request(points);
        world()->poll();
    } catch (const Error& e) { // e.g. over the memory budget: keep the tiles there are
        panel_.message = e.what();
    }
    syncWorldTiles(*state_->gpu.renderer, *world());
    panel_.worldTiles = world()->residentCount();
    panel_.worldPending = world()->pendingTiles();
    panel_.worldMiB = double(world()->residentBytes() + world()->keptStateBytes()) / 1048576.0;
    panel_.worldBudgetMiB = double(state_->resources.scene.world.memoryBudgetBytes) / 1048576.0;
    panel_.worldGenerated = world()->stats().generated;
    panel_.worldEvicted = world()->stats().evicted;
}

void Viewer::resetCameraAndRover() {
    const Scene& scene = state_->resources.scene;
    Camera c = sceneCamera(scene, world() ? cameraGround(scene, 0.0) : state_->resources.terrain, 16, 16, 0.0);
    camera_ = FlyCamera(c.position, c.position + glm::dvec3(c.worldFromCamera[2]));
    rover_.deactivate();
    driving_ = false;
}

float Viewer::canopyHeight() const {
    float top = 0.0f;
    const VegetationParams& v = state_->resources.scene.vegetation;
    for (uint32_t i = 0; i < v.categoryCount; ++i)
        top = std::max(top, v.categories[i].height * (1.0f + v.categories[i].heightVariation));
    return top;
}

void Viewer::reload() {
    Scene previous = state_->resources.scene;
    try {
        Scene scene = loadScene(scenePath_, std::nullopt, options_.allowAssets);
        panel_.wind = scene.wind;
        panel_.lod = scene.lod;
        panel_.density = scene.vegetation.densityMultiplier;
        rebuild(scene, false);
        panel_.message = "reloaded " + scenePath_;
        std::fprintf(stderr, "sward-view: %s\n", panel_.message.c_str());
    } catch (const Error& e) {
        // Keep showing the previous scene: a half-edited file must not close the viewer.
        panel_.message = std::string("reload failed: ") + e.what();
        std::fprintf(stderr, "sward-view: %s\n", panel_.message.c_str());
        if (!state_) rebuild(previous, false); // the new scene failed after the old one was released
    }
    sceneTime_ = modificationTime(scenePath_);
}

void Viewer::onKey(int key, int action, int) {
    if (action != GLFW_PRESS || (ui_ && ui_->wantsKeyboard())) return;
    applyKey(key, panel_, uiVisible_, window_.handle);
}

void Viewer::handleInput(double dt) {
    const bool keyboard = !(ui_ && ui_->wantsKeyboard());
    const bool panelHasMouse = ui_ && ui_->wantsMouse();
    FlyInput input = flyControls_.read(window_.handle, keyboard && !driving_, panelHasMouse);
    const double scroll = flyControls_.takeScroll();
    if (scroll != 0.0 && !panelHasMouse) camera_.scaleSpeed(scroll);
    if (!driving_) {
        camera_.update(input, dt);
        glm::dvec3 p = camera_.position();
        camera_.clampAbove(groundHeight(glm::dvec2(p)), 0.3);
    }
}

void Viewer::applyPanel() {
    if (panel_.toggleDrive) {
        Camera follow = viewCamera({16, 16});
        driving_ = !driving_;
        if (driving_ && !rover_.active()) spawnRover();
        // Back to flying from where the follow camera was; the rover stays (and keeps pushing the grass).
        if (!driving_) camera_ = FlyCamera(follow.position, follow.position + glm::dvec3(follow.worldFromCamera[2]));
        panel_.toggleDrive = false;
    }
    if (panel_.step) {
        stepPending_ = true;
        panel_.step = false;
    }
    if (panel_.reload) {
        panel_.reload = false;
        reload();
    }
    if (panel_.applyDensity) applyDensity();
    if (uint32_t(state_->gpu.renderer->samples()) != samples()) rebuild(state_->resources.scene, true);
    if (panel_.screenshot) {
        panel_.screenshot = false;
        screenshotPending_ = true;
    }
    state_->resources.scene.wind = panel_.wind;
    state_->resources.scene.lod = panel_.lod;
    if (VegetationRenderer* v = state_->gpu.renderer->vegetation()) v->setWindAndLod(panel_.wind, panel_.lod);
    state_->gpu.renderer->setDebugFlags((panel_.lodColors ? gpu::kDebugLodColors : 0u) |
                                        (panel_.updatedPlants ? gpu::kDebugUpdatedPlants : 0u));
}

void Viewer::applyDensity() {
    panel_.applyDensity = false;
    Scene scene = state_->resources.scene;
    const float previous = scene.vegetation.densityMultiplier;
    try {
        rebuild(scene, false);
        panel_.message = "density x" + std::to_string(panel_.density) + " applied (interaction reset)";
    } catch (const Error& e) {
        // E.g. over the scene's memory budget: keep the previous density.
        panel_.message = std::string("density not applied: ") + e.what();
        panel_.density = previous;
        rebuild(scene, false);
    }
}

void Viewer::run() {
    lastFrame_ = Clock::now();
    while (!glfwWindowShouldClose(window_.handle)) {
        if (headless() && frame_ >= options_.frames) break;
        require(!headless() || ++attempts_ < uint64_t(options_.frames) * 20 + 500,
                "could not present " + std::to_string(options_.frames) + " frames (the window stayed minimised)");
        glfwPollEvents();
        hooks_.apply(frame_, window_.handle, [this](int key) { onKey(key, GLFW_PRESS, 0); });
        const double dt = advanceClocks();
        handleInput(dt);
        applyPanel();
        SwapchainImage image;
        if (!swapchain_.acquire(frame_, window_.framebufferExtent(), image)) {
            if (!headless()) glfwWaitEventsTimeout(0.05); // minimised: sleep instead of spinning
            continue;
        }
        renderFrame(image, dt);
    }
    ctx_.submitter.waitIdle();
    printSummary();
}

// Returns the frame's time step (at most 0.25 s), feeds the simulation's tick clock and notices scene file edits.
double Viewer::advanceClocks() {
    auto now = Clock::now();
    double dt = std::min(std::chrono::duration<double>(now - lastFrame_).count(), 0.25);
    lastFrame_ = now;
    if (!panel_.paused) tickClock_ = std::min(tickClock_ + dt, 4.0 * state_->resources.scene.sequence.timeStep);

    // Reload the scene when its file changes (checked twice a second; editors write in bursts).
    if (!headless() && now - lastReloadCheck_ > std::chrono::milliseconds(500)) {
        lastReloadCheck_ = now;
        if (modificationTime(scenePath_) != sceneTime_) panel_.reload = true;
    }
    return dt;
}

void Viewer::renderFrame(const SwapchainImage& image, double dt) {
    const uint32_t slot = uint32_t(frame_ % gpu::kFramesInFlight);
    // The slot's previous frame has completed (acquire waited for it): its timings can be read.
    panel_.passTimes = timers_[slot]->read();
    frameTimes_.push_back(float(dt * 1000.0));
    if (frameTimes_.size() > 120) frameTimes_.erase(frameTimes_.begin());

    VkExtent2D extent = swapchain_.extent();
    ensureTargets(extent);
    Camera camera = viewCamera(extent);
    streamWorld(camera);
    buildOverlay(camera);
    updatePanel();

    const bool capture = headless() && frame_ + 1 == options_.frames && !options_.screenshot.empty();
    const bool keyShot = screenshotPending_;
    screenshotPending_ = false;
    RenderTarget* truth = keyShot ? &screenshots_.prepareKeyShot(extent) : nullptr;
    if (capture && swapchain_.supportsTransferSrc()) screenshots_.prepareSwapchainCapture(extent);

    uint64_t serial = recordFrame(image, camera, truth, capture);
    swapchain_.present(frame_, serial, image);
    ++frame_;
    writeCaptures(serial, keyShot, capture);
}

// Shows the frame's state in the panel (when visible) and takes its edits (applied next frame).
void Viewer::updatePanel() {
    Simulation* sim = state_->gpu.simulation.get();
    panel_.frameTimes = frameTimes_;
    panel_.cameraSpeed = camera_.speed();
    panel_.driving = driving_;
    if (sim) {
        panel_.tick = sim->nextTick();
        panel_.simulationSeconds = double(sim->nextTick()) * state_->resources.scene.sequence.timeStep;
        panel_.activeFieldCount = sim->hasPlants() ? sim->world().activeFields().size() : 0;
        panel_.contacts = sim->lastTick().contacts.size();
        panel_.collisionMs = sim->lastTick().stats.cpuMs;
    }
    if (uiVisible_) ui_->panel(panel_);
}

void Viewer::tickSimulation(VkCommandBuffer cmd, GpuTimers& timers) {
    Simulation* sim = state_->gpu.simulation.get();
    const double step = state_->resources.scene.sequence.timeStep;
    bool run = false;
    if (stepPending_)
        run = true;
    else if (!panel_.paused)
        run = options_.frames > 0 || tickClock_ >= step; // --frames: one tick per frame
    stepPending_ = false;
    if (!run) return;
    tickClock_ = std::max(tickClock_ - step, 0.0);
    if (rover_.active())
        rover_.step(window_.handle, driving_ && !(ui_ && ui_->wantsKeyboard()), options_.autodrive, step);
    if (WorldSimulation* ws = state_->gpu.worldSimulation.get()) {
        worldDrive_->prepareTick(*ws, *world(),
                                 rover_.active() ? rover_.wheelColliders(roverGround(), roverIndex())
                                                 : std::vector<Collider>{});
        timers.begin(cmd, "interaction");
        ws->recordNextTick(cmd, uint32_t(ws->nextTick() % gpu::kFrameDataSlots));
        timers.end(cmd);
    }
    if (!sim) return;
    if (rover_.active())
        sim->setExternalColliders(rover_.wheelColliders(state_->resources.terrain, roverIndex()));
    else
        sim->setExternalColliders({});
    timers.begin(cmd, "interaction");
    sim->recordNextTick(cmd, uint32_t(sim->nextTick() % gpu::kFrameDataSlots));
    timers.end(cmd);
}

Camera Viewer::viewCamera(VkExtent2D extent) const {
    double fov = state_->resources.scene.camera.fovYDegrees;
    if (!driving_) return camera_.camera(fov, extent.width, extent.height);
    return rover_.followCamera(roverGround(), fov, extent.width, extent.height);
}

void Viewer::buildOverlay(const Camera& camera) {
    Overlay& overlay = *state_->overlay;
    overlay.clear();
    glm::vec3 eye(camera.position);
    Simulation* sim = state_->gpu.simulation.get();
    if (panel_.activeFields && state_->resources.tile) {
        std::vector<uint8_t> active(state_->resources.tile->fields.size(), 0);
        if (sim && sim->hasPlants())
            for (uint32_t f : sim->world().activeFields()) active[f] = 1;
        // Just above the canopy: at the ground the grass would hide the outlines.
        overlay.fields(*state_->resources.tile, state_->resources.terrain, active, eye, 200.0f, 1.1f * canopyHeight());
    }
    if (panel_.clusterBounds && state_->resources.tile) overlay.clusters(*state_->resources.tile, eye, 40.0f);
    // All colliders with the overlay on; without a rover model, the rover's wheels always (they are how it is seen).
    const bool wheelsOnly = rover_.active() && !state_->roverObject;
    const WorldSimulation* ws = state_->gpu.worldSimulation.get();
    if ((sim || ws) && (panel_.colliders || wheelsOnly)) {
        for (const Collider& c : sim ? sim->lastColliders() : ws->lastColliders())
            if (panel_.colliders || RoverControl::isWheel(c, roverIndex()))
                overlay.collider(c, c.kind == ColliderKind::Gust ? glm::vec3(0.5f, 1.5f, 3.0f)
                                                                 : glm::vec3(4.0f, 4.0f, 0.5f));
    }
    rover_.show(state_->gpu.renderer->objects(), state_->roverObject, roverGround(), overlay);
    overlay.upload(uint32_t(frame_));
}

void Viewer::ensureTargets(VkExtent2D extent) {
    if (main_ && main_->desc().width == extent.width && main_->desc().height == extent.height &&
        uint32_t(main_->desc().samples) == samples())
        return;
    ctx_.submitter.waitIdle();
    main_ = std::make_unique<RenderTarget>(ctx_, mainPassTargetDesc(extent.width, extent.height, samples()));
    screenshots_.dropTruthTarget(); // created on the next screenshot, at this size
    ++recreations_;
}

// Records and submits the frame: interaction tick, scene passes, key screenshot readbacks (when `truth`, the
// screenshot's depth target, is given), present pass, panel and the hand-off to presentation (through the
// swapchain capture when `capture`). Returns the submission's serial.
uint64_t Viewer::recordFrame(const SwapchainImage& image, const Camera& camera, RenderTarget* truth, bool capture) {
    const bool keyShot = truth != nullptr;
    VkCommandBuffer cmd = ctx_.submitter.begin();
    GpuTimers& timers = *timers_[frame_ % gpu::kFramesInFlight];
    timers.reset(cmd);
    tickSimulation(cmd, timers);
    Simulation* sim = state_->gpu.simulation.get();
    const WorldSimulation* ws = state_->gpu.worldSimulation.get();
    const uint64_t tick = sim ? sim->nextTick() : ws ? ws->nextTick() : 0;
    const double simTime = double(tick) * state_->resources.scene.sequence.timeStep;
    state_->gpu.renderer->record(cmd, *main_, truth, camera, simTime, uint32_t(frame_), &timers);
    if (keyShot) screenshots_.recordKeyShotReadback(cmd, *main_);
    timers.begin(cmd, "present");
    present_.record(cmd, swapchain_, image, main_->output(0), panel_.exposure);
    timers.end(cmd);
    if (uiVisible_) {
        timers.begin(cmd, "panel");
        ui_->record(cmd, swapchain_, image.index);
        timers.end(cmd);
    }
    if (capture && swapchain_.supportsTransferSrc())
        screenshots_.recordSwapchainCapture(cmd, image, swapchain_.extent());
    else
        PresentPass::recordToPresent(cmd, image.image);
    if (keyShot || capture) transferToHostBarrier(cmd);
    return ctx_.submitter.submit(cmd, image.acquired, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, image.finished);
}

// Waits for frame `serial` and writes the key screenshot and / or the headless capture it read back.
void Viewer::writeCaptures(uint64_t serial, bool keyShot, bool capture) {
    const VkExtent2D extent = swapchain_.extent();
    if (keyShot) {
        ctx_.submitter.wait(serial);
        panel_.message = screenshots_.writeKeyShot(*main_, state_->resources.scene.name, panel_.exposure);
        std::fprintf(stderr, "sward-view: %s\n", panel_.message.c_str());
    }
    if (capture) {
        ctx_.submitter.wait(serial);
        if (swapchain_.supportsTransferSrc())
            screenshots_.writeSwapchainPng(options_.screenshot, extent, swapchain_.format());
        else
            Screenshots::writeTonemappedPng(options_.screenshot, *main_, extent, panel_.exposure);
    }
}

void Viewer::printSummary() const {
    VkExtent2D e = swapchain_.extent();
    std::printf("sward-view: %s, %llu frame(s), final size %ux%u, %llu swapchain creation(s), %u render-target "
                "size(s), tick %llu\n",
                state_->resources.scene.name.c_str(), (unsigned long long)frame_, e.width, e.height,
                (unsigned long long)swapchain_.generation(), recreations_,
                (unsigned long long)(state_->gpu.simulation        ? state_->gpu.simulation->nextTick()
                                     : state_->gpu.worldSimulation ? state_->gpu.worldSimulation->nextTick()
                                                                   : 0));
    if (world())
        std::printf("sward-view: world: %u tile(s) resident, %u pending, %llu generated, %llu evicted, %.0f MiB\n",
                    world()->residentCount(), world()->pendingTiles(), (unsigned long long)world()->stats().generated,
                    (unsigned long long)world()->stats().evicted, double(world()->residentBytes()) / 1048576.0);
    if (worldDrive_ && rover_.active()) {
        const WorldSimulation* ws = state_->gpu.worldSimulation.get();
        std::printf("sward-view: world: %s; tick %llu, %llu contact(s), %zu rut block(s)\n",
                    worldDrive_->summary().c_str(), (unsigned long long)(ws ? ws->nextTick() : 0),
                    (unsigned long long)(ws ? ws->contacts() : 0), ws ? ws->tracks().blocks().size() : size_t(0));
    }
}

} // namespace

void runViewer(const ViewerOptions& options) {
    // A bad scene file fails fast, before a window or a device exists.
    loadScene(options.scenePath.empty() ? defaultScenePath() : options.scenePath, std::nullopt, options.allowAssets);
    parsePresses(options.press);
    GlfwLibrary glfw;
    Window window(options.width, options.height, "sward-view");
    Context ctx(windowDeviceOptions(options.device, options.validation, window.handle));
    {
        Viewer viewer(options, window, ctx);
        viewer.run();
    }
    // Counted after every viewer object is gone, so teardown mistakes fail the run too.
    uint32_t messages = ctx.device.validationMessageCount();
    require(messages == 0, std::to_string(messages) + " Vulkan validation message(s) were reported (see above)");
}

} // namespace sward

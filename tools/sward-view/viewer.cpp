#include "viewer.h"

#include "engine/barriers.h"
#include "engine/context.h"
#include "fly_camera.h"
#include "io/image_files.h"
#include "scene/objects.h"
#include "overlay.h"
#include "engine/pipelines.h"
#include "engine/render_target.h"
#include "scene/scene.h"
#include "render/object_renderer.h"
#include "render/scene_renderer.h"
#include "render/simulation.h"
#include "engine/swapchain.h"
#include "engine/timestamps.h"
#include "ui.h"
#include "render/vegetation_renderer.h"

#include <GLFW/glfw3.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <sstream>
#include <unistd.h>

#ifndef SWARD_SOURCE_DIR
#define SWARD_SOURCE_DIR "."
#endif

namespace sward {

namespace {

using Clock = std::chrono::steady_clock;

// GLFW is a process-wide library: initialised once per viewer run, errors turned into one-line messages.
std::string lastGlfwError;
bool glfwReady = false;

struct GlfwLibrary {
    GlfwLibrary() {
        // Until GLFW is up its errors become part of our one error line; afterwards they are logged.
        glfwSetErrorCallback([](int code, const char* text) {
            lastGlfwError = text;
            if (glfwReady) std::fprintf(stderr, "sward: GLFW error %d: %s\n", code, text);
        });
        const bool ok = glfwInit() == GLFW_TRUE; // before the message is built: it quotes GLFW's error
        require(ok, "cannot open a window: " + lastGlfwError + " (no display? headless, run it inside xvfb-run)");
        glfwReady = true;
        require(glfwVulkanSupported() == GLFW_TRUE, "GLFW found no Vulkan loader with window-system support");
    }
    ~GlfwLibrary() {
        glfwReady = false;
        glfwTerminate();
    }
};

struct Window {
    GLFWwindow* handle = nullptr;
    Window(uint32_t width, uint32_t height, const std::string& title) {
        glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
        handle = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
        require(handle != nullptr, "could not create a " + std::to_string(width) + "x" + std::to_string(height) + " window");
    }
    ~Window() { glfwDestroyWindow(handle); }
    VkExtent2D framebufferExtent() const {
        int w = 0, h = 0;
        glfwGetFramebufferSize(handle, &w, &h);
        return {uint32_t(std::max(w, 0)), uint32_t(std::max(h, 0))};
    }
};

DeviceOptions deviceOptions(const ViewerOptions& options, GLFWwindow* window) {
    DeviceOptions d{.deviceFilter = options.device, .validation = options.validation || DeviceOptions{}.validation};
    uint32_t count = 0;
    const char** extensions = glfwGetRequiredInstanceExtensions(&count);
    require(extensions != nullptr, "GLFW cannot present Vulkan images on this display");
    d.instanceExtensions.assign(extensions, extensions + count);
    d.createSurface = [window](VkInstance instance) {
        VkSurfaceKHR surface = VK_NULL_HANDLE;
        VK_CHECK(glfwCreateWindowSurface(instance, window, nullptr, &surface));
        return surface;
    };
    return d;
}

std::string defaultScenePath() {
    if (std::filesystem::exists("examples/meadow.json")) return "examples/meadow.json";
    return std::string(SWARD_SOURCE_DIR) + "/examples/meadow.json";
}

// The rover the user drives: a pose integrated per simulation tick (so tracks do not depend on frame rate).
struct Rover {
    glm::dvec2 position{0.0};
    double heading = 0.0; // radians from +x towards +y
    double speed = 0.0;   // m/s, negative = reversing
    glm::dvec2 direction() const { return {std::cos(heading), std::sin(heading)}; }
    void step(double throttle, double steer, double autodrive, double dt) {
        if (autodrive != 0.0) speed = autodrive;
        else {
            double target = throttle > 0 ? 4.0 : throttle < 0 ? -2.0 : 0.0;
            double accel = throttle != 0 ? 3.0 : 5.0; // braking is quicker than accelerating
            speed += std::clamp(target - speed, -accel * dt, accel * dt);
        }
        heading += steer * 1.2 * dt * (speed < 0 ? -1.0 : 1.0) * std::min(std::abs(speed) / 1.0, 1.0);
        position += direction() * (speed * dt);
    }
};

// Everything that depends on the scene file; rebuilt on reload, density or MSAA changes. Members are
// declared in construction order, so the simulation (which uses the renderer's buffers) is destroyed first.
struct SceneState {
    Scene scene;
    Heightfield terrain;
    std::optional<VegetationTile> tile;
    std::vector<ObjectModel> models; // the scene's glTF objects (drawn and colliding)
    std::optional<size_t> roverObject; // the keyboard rover's glTF model: the object after the scene's own
    std::unique_ptr<SceneRenderer> renderer;
    std::unique_ptr<Simulation> simulation;
    std::unique_ptr<Overlay> overlay;
};

// The default rover model (sward-rover), drawn where the keyboard rover drives; none if it is not installed.
std::string roverModelPath() {
    for (std::string path : {std::string("examples/assets/rover.gltf"), std::string(SWARD_SOURCE_DIR) + "/examples/assets/rover.gltf"})
        if (std::filesystem::exists(path)) return path;
    return {};
}

std::unique_ptr<SceneState> loadSceneState(Context& ctx, const Scene& sceneIn, uint32_t samples) {
    // The keyboard rover is drawn as one more scene object without colliders (its wheels collide through
    // Simulation::setExternalColliders); ObjectRenderer::place moves it every frame.
    Scene scene = sceneIn;
    std::optional<size_t> roverObject;
    if (std::string model = roverModelPath(); !model.empty()) {
        ObjectParams rover;
        rover.name = "sward-view rover";
        rover.model = model;
        rover.path.points = {glm::dvec2(0.0)};
        roverObject = scene.objects.size();
        scene.objects.push_back(rover);
    }
    auto state = std::make_unique<SceneState>(SceneState{scene, buildTerrain(scene), std::nullopt,
                                                         loadObjectModels(scene.objects, scene.source), roverObject,
                                                         nullptr, nullptr, nullptr});
    std::optional<Atlas> atlas;
    if (scene.vegetationEnabled) {
        state->tile = buildVegetation(state->scene, state->terrain);
        atlas = buildAtlas(state->scene);
    }
    VkSampleCountFlagBits sampleBits = samples == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT;
    state->renderer = std::make_unique<SceneRenderer>(ctx, state->scene, state->terrain, sampleBits,
                                                      state->tile ? &*state->tile : nullptr, atlas ? &*atlas : nullptr,
                                                      &state->models);
    if (state->tile && state->renderer->vegetation())
        state->simulation = std::make_unique<Simulation>(ctx, state->scene, state->terrain, *state->tile,
                                                         state->renderer->vegetation()->buffers());
    if (state->simulation) state->simulation->setObjectModels(&state->models);
    if (state->roverObject && state->renderer->objects()) state->renderer->objects()->setVisible(*state->roverObject, false);
    state->overlay = std::make_unique<Overlay>(ctx, sampleBits);
    return state;
}

// "FRAME:KEY,..." -> (frame, GLFW key) pairs.
std::vector<std::pair<uint64_t, int>> parsePresses(const std::string& text) {
    std::vector<std::pair<uint64_t, int>> presses;
    std::stringstream list(text);
    for (std::string item; std::getline(list, item, ',');) {
        size_t colon = item.find(':');
        std::string frame = item.substr(0, colon), key = colon == std::string::npos ? "" : item.substr(colon + 1);
        int code = GLFW_KEY_UNKNOWN;
        if (key.size() == 1 && key[0] >= 'a' && key[0] <= 'z') code = GLFW_KEY_A + (key[0] - 'a');
        else if (key.size() == 1 && key[0] >= '0' && key[0] <= '9') code = GLFW_KEY_0 + (key[0] - '0');
        else if (key == "space") code = GLFW_KEY_SPACE;
        else if (key == "f12") code = GLFW_KEY_F12;
        else if (key == "esc") code = GLFW_KEY_ESCAPE;
        if (frame.empty() || frame.find_first_not_of("0123456789") != std::string::npos || code == GLFW_KEY_UNKNOWN)
            throw Error("bad --press item '" + item + "': expected FRAME:KEY with KEY a-z, 0-9, space, f12 or esc");
        presses.emplace_back(std::stoull(frame), code);
    }
    return presses;
}

std::filesystem::file_time_type modificationTime(const std::string& path) {
    std::error_code ec;
    auto t = std::filesystem::last_write_time(path, ec);
    return ec ? std::filesystem::file_time_type{} : t;
}

class Viewer {
public:
    Viewer(const ViewerOptions& options, Window& window, Context& ctx);
    ~Viewer();
    void run();

private:
    void rebuild(const Scene& scene, bool keepInteraction);
    void reload();
    void resetCameraAndRover();
    void spawnRover();
    float canopyHeight() const;
    void handleInput(double dt);
    void onKey(int key, int action, int mods);
    void tickSimulation(VkCommandBuffer cmd, GpuTimers& timers);
    Camera viewCamera(VkExtent2D extent) const;
    void buildOverlay(const Camera& camera);
    void ensureTargets(VkExtent2D extent);
    void recordPresent(VkCommandBuffer cmd, const SwapchainImage& image);
    void writeScreenshot();
    void writeSwapchainPng(const std::string& path, VkExtent2D extent);
    void applyPanel();
    uint32_t samples() const { return panel_.msaa ? 4u : 1u; }

    ViewerOptions options_;
    std::string scenePath_;
    Window& window_;
    Context& ctx_;
    Swapchain swapchain_;
    std::unique_ptr<Ui> ui_;
    std::unique_ptr<SceneState> state_;
    std::unique_ptr<RenderTarget> main_, truth_;
    Buffer colorReadback_, depthReadback_, swapchainReadback_;
    Pipeline presentPipeline_;
    VkFormat presentFormat_ = VK_FORMAT_UNDEFINED;
    VkSampler sampler_ = VK_NULL_HANDLE;
    std::unique_ptr<GpuTimers> timers_[Swapchain::kFramesInFlight];

    PanelState panel_;
    FlyCamera camera_;
    Rover rover_;
    VehicleParams roverParams_;
    bool driving_ = false;     // camera follows the rover, arrow keys drive it
    bool roverActive_ = false; // the rover exists: it collides and is drawn (from the first F on)
    bool uiVisible_ = true, looking_ = false;
    glm::dvec2 lastCursor_{0.0};
    double scroll_ = 0.0, tickClock_ = 0.0;
    uint64_t frame_ = 0, screenshotCount_ = 0;
    bool screenshotPending_ = false, stepPending_ = false;
    std::filesystem::file_time_type sceneTime_{};
    Clock::time_point lastReloadCheck_{};
    std::vector<std::pair<uint64_t, int>> presses_;
    uint32_t recreations_ = 0;
};

Viewer::Viewer(const ViewerOptions& options, Window& window, Context& ctx)
    : options_(options), scenePath_(options.scenePath.empty() ? defaultScenePath() : options.scenePath),
      window_(window), ctx_(ctx), swapchain_(ctx, ctx.device.surface(), window.framebufferExtent(), options.vsync) {
    Scene scene = loadScene(scenePath_);
    sceneTime_ = modificationTime(scenePath_);
    uint32_t samples = options.samples.value_or(scene.render.samples);
    require(samples == 1 || samples == 4, "--samples must be 1 or 4 (got " + std::to_string(samples) + ")");
    panel_.msaa = samples == 4;
    panel_.wind = scene.wind;
    panel_.lod = scene.lod;
    panel_.density = scene.vegetation.densityMultiplier;
    panel_.device = ctx_.device.name();
    for (std::string item; const char c : options.overlays + ",") {
        if (c != ',') {
            item += c;
            continue;
        }
        if (item == "lod") panel_.lodColors = true;
        else if (item == "active-fields") panel_.activeFields = true;
        else if (item == "updated-plants") panel_.updatedPlants = true;
        else if (item == "clusters") panel_.clusterBounds = true;
        else if (item == "colliders") panel_.colliders = true;
        else if (!item.empty())
            throw Error("unknown overlay '" + item + "' (use lod, active-fields, updated-plants, clusters, colliders)");
        item.clear();
    }
    uiVisible_ = options.showUi;
    presses_ = parsePresses(options.press);

    for (auto& t : timers_) t = std::make_unique<GpuTimers>(ctx_.device, 16);
    VkSamplerCreateInfo sampler{
        .sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
        .magFilter = VK_FILTER_NEAREST,
        .minFilter = VK_FILTER_NEAREST,
        .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
        .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
    };
    VK_CHECK(vkCreateSampler(ctx_.vk(), &sampler, nullptr, &sampler_));

    // GLFW callbacks go in before ImGui's backend, which chains to them.
    glfwSetWindowUserPointer(window_.handle, this);
    glfwSetKeyCallback(window_.handle, [](GLFWwindow* w, int key, int, int action, int mods) {
        static_cast<Viewer*>(glfwGetWindowUserPointer(w))->onKey(key, action, mods);
    });
    glfwSetScrollCallback(window_.handle, [](GLFWwindow* w, double, double y) {
        static_cast<Viewer*>(glfwGetWindowUserPointer(w))->scroll_ += y;
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
    truth_.reset();
    for (Buffer* b : {&colorReadback_, &depthReadback_, &swapchainReadback_})
        if (*b) destroyBuffer(ctx_, *b);
    destroyPipeline(ctx_.device, presentPipeline_);
    vkDestroySampler(ctx_.vk(), sampler_, nullptr);
    for (auto& t : timers_) t.reset();
}

void Viewer::rebuild(const Scene& sceneIn, bool keepInteraction) {
    Scene scene = sceneIn; // may be state_->scene, which is about to go
    // Interaction state survives an MSAA change (same plants): read it back, rebuild, upload it again.
    std::vector<gpu::PlantDynamic> dynamics;
    std::string stateFile;
    if (keepInteraction && state_ && state_->simulation) {
        stateFile = (std::filesystem::temp_directory_path() / ("sward-view-" + std::to_string(getpid()) + ".state")).string();
        state_->simulation->world().saveState(stateFile, state_->simulation->gpu().readDynamics());
    }
    ctx_.submitter.waitIdle();
    state_.reset();
    main_.reset();
    truth_.reset();
    // Kept interaction needs the very same plants; otherwise the panel's density applies.
    if (!keepInteraction) scene.vegetation.densityMultiplier = panel_.density;
    state_ = loadSceneState(ctx_, scene, samples());
    if (!stateFile.empty() && state_->simulation) {
        state_->simulation->gpu().writeDynamics(state_->simulation->world().restoreState(stateFile));
        std::filesystem::remove(stateFile);
    }
    state_->renderer->setMainPassOverlay([this](VkCommandBuffer cmd, const DescriptorBinding& frame) {
        state_->overlay->draw(cmd, frame, uint32_t(frame_));
    });
    panel_.scene = state_->scene.name + " (" + scenePath_ + ")";
    panel_.fieldCount = state_->tile ? state_->tile->fields.size() : 0;
    roverParams_ = state_->scene.actors.vehicles.empty() ? VehicleParams{} : state_->scene.actors.vehicles[0];
}

void Viewer::resetCameraAndRover() {
    Camera c = sceneCamera(state_->scene, state_->terrain, 16, 16, 0.0);
    camera_ = FlyCamera(c.position, c.position + glm::dvec3(c.worldFromCamera[2]));
    roverActive_ = driving_ = false;
}

void Viewer::spawnRover() {
    // Where the fly camera looks (on the ground within 300 m), else 6 m ahead, heading the way it looks.
    glm::dvec3 eye = camera_.position(), forward = camera_.forward();
    glm::dvec2 flat = glm::length(glm::dvec2(forward)) > 1e-6 ? glm::normalize(glm::dvec2(forward)) : glm::dvec2(1, 0);
    std::optional<double> hit = state_->terrain.raycast(eye, forward, 300.0);
    glm::dvec2 at = hit ? glm::dvec2(eye + forward * *hit) : glm::dvec2(eye) + flat * 6.0;
    rover_ = Rover{at, std::atan2(flat.y, flat.x), 0.0};
    roverActive_ = true;
}

float Viewer::canopyHeight() const {
    float top = 0.0f;
    const VegetationParams& v = state_->scene.vegetation;
    for (uint32_t i = 0; i < v.categoryCount; ++i)
        top = std::max(top, v.categories[i].height * (1.0f + v.categories[i].heightVariation));
    return top;
}

void Viewer::reload() {
    Scene previous = state_->scene;
    try {
        Scene scene = loadScene(scenePath_);
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
    switch (key) {
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window_.handle, GLFW_TRUE); break;
    case GLFW_KEY_F: panel_.toggleDrive = true; break;
    case GLFW_KEY_SPACE: panel_.paused = !panel_.paused; break;
    case GLFW_KEY_N: panel_.step = true; break;
    case GLFW_KEY_F12:
    case GLFW_KEY_P: panel_.screenshot = true; break;
    case GLFW_KEY_R: panel_.reload = true; break;
    case GLFW_KEY_H: uiVisible_ = !uiVisible_; break;
    case GLFW_KEY_M: panel_.msaa = !panel_.msaa; break;
    case GLFW_KEY_1: panel_.lodColors = !panel_.lodColors; break;
    case GLFW_KEY_2: panel_.activeFields = !panel_.activeFields; break;
    case GLFW_KEY_3: panel_.updatedPlants = !panel_.updatedPlants; break;
    case GLFW_KEY_4: panel_.clusterBounds = !panel_.clusterBounds; break;
    case GLFW_KEY_5: panel_.colliders = !panel_.colliders; break;
    default: break;
    }
}

void Viewer::handleInput(double dt) {
    GLFWwindow* w = window_.handle;
    auto down = [&](int key) { return glfwGetKey(w, key) == GLFW_PRESS; };
    const bool keyboard = !(ui_ && ui_->wantsKeyboard());
    // Mouse look while the right button is held (or the left one outside the panel).
    bool wantLook = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                    (glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS && !(ui_ && ui_->wantsMouse()));
    glm::dvec2 cursor;
    glfwGetCursorPos(w, &cursor.x, &cursor.y);
    FlyInput input;
    if (wantLook && looking_) input.turn = cursor - lastCursor_;
    looking_ = wantLook;
    lastCursor_ = cursor;
    if (keyboard && !driving_) {
        input.move.y = (down(GLFW_KEY_W) ? 1.0 : 0.0) - (down(GLFW_KEY_S) ? 1.0 : 0.0);
        input.move.x = (down(GLFW_KEY_D) ? 1.0 : 0.0) - (down(GLFW_KEY_A) ? 1.0 : 0.0);
        input.move.z = (down(GLFW_KEY_E) ? 1.0 : 0.0) - (down(GLFW_KEY_Q) ? 1.0 : 0.0);
        input.fast = down(GLFW_KEY_LEFT_SHIFT) || down(GLFW_KEY_RIGHT_SHIFT);
    }
    if (scroll_ != 0.0 && !(ui_ && ui_->wantsMouse())) camera_.scaleSpeed(scroll_);
    scroll_ = 0.0;
    if (!driving_) {
        camera_.update(input, dt);
        glm::dvec3 p = camera_.position();
        camera_.clampAbove(state_->terrain.height(glm::vec2(p)), 0.3);
    }
}

Camera Viewer::viewCamera(VkExtent2D extent) const {
    double fov = state_->scene.camera.fovYDegrees;
    if (!driving_) return camera_.camera(fov, extent.width, extent.height);
    // Follow: behind and above the rover, looking just over it.
    glm::dvec2 back = glm::dvec2(rover_.position) - rover_.direction() * 6.0;
    glm::dvec3 eye(back, state_->terrain.height(glm::vec2(back)) + 3.5);
    glm::dvec3 target(rover_.position, state_->terrain.height(glm::vec2(rover_.position)) + 0.4);
    return Camera::lookAt(eye, target, glm::dvec3(0, 0, 1), fov, extent.width, extent.height);
}

void Viewer::tickSimulation(VkCommandBuffer cmd, GpuTimers& timers) {
    Simulation* sim = state_->simulation.get();
    const double step = state_->scene.sequence.timeStep;
    bool run = false;
    if (stepPending_) run = true;
    else if (!panel_.paused) run = options_.frames > 0 || tickClock_ >= step; // --frames: one tick per frame
    stepPending_ = false;
    if (!run) return;
    tickClock_ = std::max(tickClock_ - step, 0.0);
    if (roverActive_) {
        GLFWwindow* w = window_.handle;
        bool keyboard = driving_ && !(ui_ && ui_->wantsKeyboard());
        auto down = [&](int key) { return keyboard && glfwGetKey(w, key) == GLFW_PRESS; };
        double throttle = (down(GLFW_KEY_UP) ? 1.0 : 0.0) - (down(GLFW_KEY_DOWN) ? 1.0 : 0.0);
        double steer = (down(GLFW_KEY_LEFT) ? 1.0 : 0.0) - (down(GLFW_KEY_RIGHT) ? 1.0 : 0.0);
        rover_.step(throttle, steer, options_.autodrive, step);
    }
    if (!sim) return;
    if (roverActive_) {
        // Ids after the scene's own vehicles, so the user's rover never shares ids with them.
        uint32_t index = uint32_t(state_->scene.actors.vehicles.size());
        sim->setExternalColliders(wheelColliders(
            roverParams_, vehicleWheelsAt(roverParams_, state_->terrain, rover_.position, rover_.direction()), index));
    } else {
        sim->setExternalColliders({});
    }
    timers.begin(cmd, "interaction");
    sim->recordNextTick(cmd, uint32_t(sim->nextTick() % InteractionGpu::kSlots));
    timers.end(cmd);
}

void Viewer::buildOverlay(const Camera& camera) {
    Overlay& overlay = *state_->overlay;
    overlay.clear();
    glm::vec3 eye(camera.position);
    Simulation* sim = state_->simulation.get();
    if (panel_.activeFields && state_->tile) {
        std::vector<uint8_t> active(state_->tile->fields.size(), 0);
        if (sim)
            for (uint32_t f : sim->world().activeFields()) active[f] = 1;
        // Just above the canopy: at the ground the grass would hide the outlines.
        overlay.fields(*state_->tile, state_->terrain, active, eye, 200.0f, 1.1f * canopyHeight());
    }
    if (panel_.clusterBounds && state_->tile) overlay.clusters(*state_->tile, eye, 40.0f);
    // All colliders with the overlay on; without a rover model, the rover's wheels always (they are how it is seen).
    const uint32_t roverIds = 1000 * (uint32_t(state_->scene.actors.vehicles.size()) + 1);
    const bool wheelsOnly = roverActive_ && !state_->roverObject;
    if (sim && (panel_.colliders || wheelsOnly)) {
        for (const Collider& c : sim->lastColliders())
            if (panel_.colliders || (c.id >= roverIds && c.id < roverIds + 4))
                overlay.collider(c, c.kind == ColliderKind::Gust ? glm::vec3(0.5f, 1.5f, 3.0f) : glm::vec3(4.0f, 4.0f, 0.5f));
    }
    if (ObjectRenderer* objects = state_->renderer->objects(); objects && state_->roverObject) {
        objects->setVisible(*state_->roverObject, roverActive_);
        if (roverActive_) objects->place(*state_->roverObject, rover_.position, rover_.heading);
    } else if (roverActive_) {
        // No rover model installed: a box over its wheels, so it can be seen while it drives.
        glm::dvec2 f = rover_.direction(), l(-f.y, f.x);
        float z = state_->terrain.height(glm::vec2(rover_.position)) + 2.0f * roverParams_.wheelRadius;
        glm::vec3 color(3.0f, 3.0f, 3.0f);
        glm::vec2 corners[4];
        for (int i = 0; i < 4; ++i)
            corners[i] = glm::vec2(rover_.position + f * ((i < 2 ? 0.5 : -0.5) * (roverParams_.wheelBase + 0.2)) +
                                   l * ((i == 0 || i == 3 ? 0.5 : -0.5) * roverParams_.trackWidth));
        for (int i = 0; i < 4; ++i) {
            overlay.line(glm::vec3(corners[i], z), glm::vec3(corners[(i + 1) % 4], z), color);
            overlay.line(glm::vec3(corners[i], z + 0.25f), glm::vec3(corners[(i + 1) % 4], z + 0.25f), color);
            overlay.line(glm::vec3(corners[i], z), glm::vec3(corners[i], z + 0.25f), color);
        }
    }
    overlay.upload(uint32_t(frame_));
}

void Viewer::ensureTargets(VkExtent2D extent) {
    if (main_ && main_->desc().width == extent.width && main_->desc().height == extent.height &&
        uint32_t(main_->desc().samples) == samples())
        return;
    ctx_.submitter.waitIdle();
    main_ = std::make_unique<RenderTarget>(ctx_, mainPassTargetDesc(extent.width, extent.height, samples()));
    truth_.reset(); // created on the next screenshot, at this size
    ++recreations_;
}

void Viewer::recordPresent(VkCommandBuffer cmd, const SwapchainImage& image) {
    if (presentFormat_ != swapchain_.format()) {
        ctx_.submitter.waitIdle();
        destroyPipeline(ctx_.device, presentPipeline_);
        presentPipeline_ = createGraphicsPipeline(
            ctx_.device,
            {.vertexShader = "present.vert",
             .fragmentShader = "present.frag",
             .cullMode = VK_CULL_MODE_NONE,
             .colorFormats = {swapchain_.format()},
             .depthTest = false,
             .depthWrite = false,
             .specialization = {/* SRGB_TARGET= */ swapchain_.srgb() ? 1u : 0u}},
            {.bindings = {layoutBinding(0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT)},
             .pushConstantSize = sizeof(float),
             .pushConstantStages = VK_SHADER_STAGE_FRAGMENT_BIT});
        presentFormat_ = swapchain_.format();
    }
    const Image& hdr = main_->output(0);
    // RenderTarget::end left the resolved image for copies; the present pass samples it instead.
    imageBarrier(cmd, hdr.handle, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                 VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    // The acquire semaphore is waited on at COLOR_ATTACHMENT_OUTPUT; this transition is chained to that wait.
    imageBarrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    VkExtent2D extent = swapchain_.extent();
    VkRenderingAttachmentInfo color{
        .sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
        .imageView = image.view,
        .imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
        .loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE, // the full-screen triangle covers every pixel
        .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
    };
    VkRenderingInfo rendering{
        .sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
        .renderArea = {{0, 0}, extent},
        .layerCount = 1,
        .colorAttachmentCount = 1,
        .pColorAttachments = &color,
    };
    vkCmdBeginRendering(cmd, &rendering);
    VkViewport viewport{0.0f, 0.0f, float(extent.width), float(extent.height), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, extent};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    bindPipeline(cmd, presentPipeline_);
    pushDescriptors(ctx_.device, cmd, presentPipeline_, {sampledImage(0, hdr.view, sampler_)});
    pushConstants(cmd, presentPipeline_, panel_.exposure);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
    // Back to where RenderTarget::begin of the next frame expects it (its transition waits for COPY).
    imageBarrier(cmd, hdr.handle, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_NONE,
                 VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE);
}

void Viewer::writeScreenshot() {
    const uint32_t w = main_->desc().width, h = main_->desc().height;
    const uint64_t pixels = uint64_t(w) * h;
    std::vector<uint16_t> rgba(pixels * 4);
    std::vector<float> depth(pixels);
    std::memcpy(rgba.data(), colorReadback_.mapped(), pixels * 8);
    std::memcpy(depth.data(), depthReadback_.mapped(), pixels * 4); // float bits written by the truth pass
    ensureWritableDirectory(options_.screenshotDir);
    char name[64];
    std::snprintf(name, sizeof name, "/%s-%04llu", state_->scene.name.c_str(), (unsigned long long)screenshotCount_++);
    std::string base = options_.screenshotDir + name;
    writeExrRgbaHalf(base + ".exr", w, h, rgba);
    writeExrDepth(base + "-depth.exr", w, h, depth);
    writePng8(base + ".png", w, h, 3, tonemapPreview(rgba, w, h, panel_.exposure));
    panel_.message = "wrote " + base + ".exr, " + base + "-depth.exr, " + base + ".png";
    std::fprintf(stderr, "sward-view: %s\n", panel_.message.c_str());
}

void Viewer::writeSwapchainPng(const std::string& path, VkExtent2D extent) {
    const uint64_t pixels = uint64_t(extent.width) * extent.height;
    const uint8_t* src = swapchainReadback_.mapped();
    const bool bgr = swapchain_.format() == VK_FORMAT_B8G8R8A8_SRGB || swapchain_.format() == VK_FORMAT_B8G8R8A8_UNORM;
    std::vector<uint8_t> rgb(pixels * 3);
    for (uint64_t p = 0; p < pixels; ++p)
        for (int c = 0; c < 3; ++c) rgb[p * 3 + c] = src[p * 4 + (bgr ? 2 - c : c)];
    std::filesystem::path parent = std::filesystem::path(path).parent_path();
    if (!parent.empty()) ensureWritableDirectory(parent.string());
    writePng8(path, extent.width, extent.height, 3, rgb);
}

void Viewer::applyPanel() {
    if (panel_.toggleDrive) {
        Camera follow = viewCamera({16, 16});
        driving_ = !driving_;
        if (driving_ && !roverActive_) spawnRover();
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
    if (panel_.applyDensity) {
        panel_.applyDensity = false;
        Scene scene = state_->scene;
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
    if (uint32_t(state_->renderer->samples()) != samples()) rebuild(state_->scene, true);
    if (panel_.screenshot) {
        panel_.screenshot = false;
        screenshotPending_ = true;
    }
    state_->scene.wind = panel_.wind;
    state_->scene.lod = panel_.lod;
    if (VegetationRenderer* v = state_->renderer->vegetation()) v->setWindAndLod(panel_.wind, panel_.lod);
    state_->renderer->setDebugFlags((panel_.lodColors ? gpu::kDebugLodColors : 0u) |
                                    (panel_.updatedPlants ? gpu::kDebugUpdatedPlants : 0u));
}

void Viewer::run() {
    const bool headless = options_.frames > 0;
    uint64_t attempts = 0;
    auto last = Clock::now();
    std::vector<float> frameTimes;
    while (!glfwWindowShouldClose(window_.handle)) {
        if (headless && frame_ >= options_.frames) break;
        require(!headless || ++attempts < uint64_t(options_.frames) * 20 + 500,
                "could not present " + std::to_string(options_.frames) + " frames (the window stayed minimised)");
        glfwPollEvents();
        // Test hooks: window changes at fixed frames, through the same code paths a user's actions take.
        if (options_.resizeAt && frame_ == options_.resizeAt->first) {
            uint32_t w = 0, h = 0;
            parseResolution(options_.resizeAt->second, w, h);
            glfwSetWindowSize(window_.handle, int(w), int(h));
            options_.resizeAt.reset();
        }
        for (auto& [at, key] : presses_)
            if (at == frame_) {
                onKey(key, GLFW_PRESS, 0);
                at = UINT64_MAX; // once, even if this frame is not presented
            }
        if (options_.minimizeAt && frame_ == *options_.minimizeAt) glfwIconifyWindow(window_.handle);
        if (options_.minimizeAt && frame_ == *options_.minimizeAt + 2) {
            glfwRestoreWindow(window_.handle);
            options_.minimizeAt.reset();
        }

        auto now = Clock::now();
        double dt = std::min(std::chrono::duration<double>(now - last).count(), 0.25);
        last = now;
        if (!panel_.paused) tickClock_ = std::min(tickClock_ + dt, 4.0 * state_->scene.sequence.timeStep);

        // Reload the scene when its file changes (checked twice a second; editors write in bursts).
        if (!headless && now - lastReloadCheck_ > std::chrono::milliseconds(500)) {
            lastReloadCheck_ = now;
            if (modificationTime(scenePath_) != sceneTime_) panel_.reload = true;
        }
        handleInput(dt);
        applyPanel();

        VkExtent2D windowExtent = window_.framebufferExtent();
        const uint32_t slot = uint32_t(frame_ % Swapchain::kFramesInFlight);
        SwapchainImage image;
        if (!swapchain_.acquire(frame_, windowExtent, image)) {
            if (!headless) glfwWaitEventsTimeout(0.05); // minimised: sleep instead of spinning
            continue;
        }
        // The slot's previous frame has completed (acquire waited for it): its timings can be read.
        panel_.passTimes = timers_[slot]->read();
        frameTimes.push_back(float(dt * 1000.0));
        if (frameTimes.size() > 120) frameTimes.erase(frameTimes.begin());

        VkExtent2D extent = swapchain_.extent();
        ensureTargets(extent);
        Camera camera = viewCamera(extent);
        buildOverlay(camera);

        Simulation* sim = state_->simulation.get();
        panel_.frameTimes = frameTimes;
        panel_.cameraSpeed = camera_.speed();
        panel_.driving = driving_;
        if (sim) {
            panel_.tick = sim->nextTick();
            panel_.simulationSeconds = double(sim->nextTick()) * state_->scene.sequence.timeStep;
            panel_.activeFieldCount = sim->world().activeFields().size();
            panel_.contacts = sim->lastTick().contacts.size();
            panel_.collisionMs = sim->lastTick().stats.cpuMs;
        }
        if (uiVisible_) ui_->panel(panel_);

        const bool capture = headless && frame_ + 1 == options_.frames && !options_.screenshot.empty();
        const bool keyShot = screenshotPending_;
        screenshotPending_ = false;
        if (keyShot) {
            if (!truth_) truth_ = std::make_unique<RenderTarget>(ctx_, truthPassTargetDesc(extent.width, extent.height));
            uint64_t pixels = uint64_t(extent.width) * extent.height;
            for (auto [buffer, bytes] : {std::pair{&colorReadback_, pixels * 8}, std::pair{&depthReadback_, pixels * 4}})
                if (!*buffer || buffer->size < bytes) {
                    if (*buffer) retireBuffer(ctx_, *buffer);
                    *buffer = createBuffer(ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::Readback);
                }
        }
        if (capture && swapchain_.supportsTransferSrc()) {
            uint64_t bytes = uint64_t(extent.width) * extent.height * 4;
            if (swapchainReadback_) retireBuffer(ctx_, swapchainReadback_);
            swapchainReadback_ = createBuffer(ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::Readback);
        }

        VkCommandBuffer cmd = ctx_.submitter.begin();
        GpuTimers& timers = *timers_[slot];
        timers.reset(cmd);
        tickSimulation(cmd, timers);
        const double simTime = sim ? double(sim->nextTick()) * state_->scene.sequence.timeStep : 0.0;
        state_->renderer->record(cmd, *main_, keyShot ? truth_.get() : nullptr, camera, simTime, uint32_t(frame_),
                                 &timers);
        if (keyShot) {
            main_->recordReadback(cmd, 0, colorReadback_);
            truth_->recordReadback(cmd, 0, depthReadback_);
        }
        timers.begin(cmd, "present");
        recordPresent(cmd, image);
        timers.end(cmd);
        if (uiVisible_) {
            timers.begin(cmd, "panel");
            ui_->record(cmd, swapchain_, image.index);
            timers.end(cmd);
        }
        if (capture && swapchain_.supportsTransferSrc()) {
            imageBarrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                         VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                         VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                         VK_ACCESS_2_TRANSFER_READ_BIT);
            VkBufferImageCopy region{.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                     .imageExtent = {extent.width, extent.height, 1}};
            vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, swapchainReadback_.handle, 1,
                                   &region);
            imageBarrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                         VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE,
                         VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE);
        } else {
            // Presentation needs no access mask: the semaphore signal orders it after the writes.
            imageBarrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                         VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                         VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE);
        }
        if (keyShot || capture) transferToHostBarrier(cmd);
        uint64_t serial = ctx_.submitter.submit(cmd, image.acquired, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                                                image.finished);
        swapchain_.present(frame_, serial, image);
        ++frame_;

        if (keyShot) {
            ctx_.submitter.wait(serial);
            writeScreenshot();
        }
        if (capture) {
            ctx_.submitter.wait(serial);
            if (swapchain_.supportsTransferSrc()) {
                writeSwapchainPng(options_.screenshot, extent);
            } else {
                // Fallback: the same tonemap from the HDR image (what the window shows, minus the panel).
                std::vector<uint8_t> bytes = main_->readback(0);
                std::vector<uint16_t> rgba(bytes.size() / 2);
                std::memcpy(rgba.data(), bytes.data(), bytes.size());
                writePng8(options_.screenshot, extent.width, extent.height, 3,
                          tonemapPreview(rgba, extent.width, extent.height, panel_.exposure));
            }
        }
    }
    ctx_.submitter.waitIdle();
    VkExtent2D e = swapchain_.extent();
    std::printf("sward-view: %s, %llu frame(s), final size %ux%u, %llu swapchain creation(s), %u render-target "
                "size(s), tick %llu\n",
                state_->scene.name.c_str(), (unsigned long long)frame_, e.width, e.height,
                (unsigned long long)swapchain_.generation(), recreations_,
                (unsigned long long)(state_->simulation ? state_->simulation->nextTick() : 0));
}

} // namespace

void runViewer(const ViewerOptions& options) {
    // A bad scene file fails fast, before a window or a device exists.
    loadScene(options.scenePath.empty() ? defaultScenePath() : options.scenePath);
    parsePresses(options.press);
    GlfwLibrary glfw;
    Window window(options.width, options.height, "sward-view");
    Context ctx(deviceOptions(options, window.handle));
    {
        Viewer viewer(options, window, ctx);
        viewer.run();
    }
    // Counted after every viewer object is gone, so teardown mistakes fail the run too.
    uint32_t messages = ctx.device.validationMessageCount();
    require(messages == 0, std::to_string(messages) + " Vulkan validation message(s) were reported (see above)");
}

} // namespace sward

// Host-owned Vulkan (engine/device.h HostVulkan): an application creates the instance, device and queue itself,
// with the validation layer and its own messenger, and hands them to sward. sward must render on them exactly what
// it renders on a device of its own, report nothing to the host's validation, and leave them alive. The host is
// the one of examples/host-app.
#include "gpu_test.h"
#include "host_application.h" // examples/host-app: the host's own Vulkan bring-up

#include "render/sequence_frame.h"
#include "scene/scene_input.h"

#include <cstring>

using namespace sward;

namespace {

// Frames 0 and 1 of the GPU test scene (a rover leaving tracks) at 96x64 on `ctx`.
std::vector<FrameImages> renderTwoFrames(Context& ctx) {
    SceneResources r = buildSceneResources(loadSceneInput(
        {.path = std::string(SWARD_TEST_DATA_DIR) + "/dataset_scene.json",
         .overrides = R"({"render.resolution": [96, 64], "render.samples": 1})"}));
    SceneGpu gpu = createSceneGpu(ctx, r, 1, SimulationMode::WhenSceneHasColliders);
    OffscreenFrame target(ctx, 96, 64, 1);
    std::vector<FrameImages> frames;
    for (uint32_t frame = 0; frame < 2; ++frame) {
        RigCameras cameras;
        frames.push_back(renderSequenceFrame(gpu, target, r, 96, 64, frame, 0.0, std::nullopt, cameras));
    }
    ctx.submitter.waitIdle();
    return frames;
}

} // namespace

TEST(HostVulkan, SwardOnTheHostsDeviceRendersWhatItRendersOnItsOwn) {
    host::HostApplication host;
    std::vector<FrameImages> onHost;
    {
        Context ctx(host.handles());
        EXPECT_TRUE(ctx.device.hostOwned());
        EXPECT_EQ(ctx.device.handle(), host.device);
        onHost = renderTwoFrames(ctx);
    } // sward's objects are gone; the host's device must still be alive and usable
    EXPECT_EQ(vkDeviceWaitIdle(host.device), VK_SUCCESS);
    EXPECT_EQ(host.messages, 0);

    Context own(DeviceOptions{.validation = true, .quiet = true});
    const std::vector<FrameImages> onOwn = renderTwoFrames(own);
    for (size_t f = 0; f < 2; ++f) {
        EXPECT_EQ(onHost[f].rgbaHalf, onOwn[f].rgbaHalf) << "frame " << f;
        EXPECT_EQ(onHost[f].rightRgbaHalf, onOwn[f].rightRgbaHalf) << "frame " << f;
        EXPECT_EQ(0, std::memcmp(onHost[f].depth.data(), onOwn[f].depth.data(), onOwn[f].depth.size() * 4));
        EXPECT_EQ(onHost[f].labels, onOwn[f].labels) << "frame " << f;
    }
    EXPECT_EQ(own.device.validationMessageCount(), 0u);
}

TEST(HostVulkan, MissingHandlesAreOneClearError) {
    try {
        Context ctx(HostVulkan{});
        FAIL() << "a host context without handles was accepted";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "host Vulkan: instance, physical device, device and queue are required");
    }
}

#include "ui.h"

#include "engine/swapchain.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace sward {

namespace {

void checkImguiVk(VkResult result) {
    if (result < 0) throw Error(std::string("Dear ImGui's Vulkan backend failed: ") + resultName(result));
}

// Every input of the viewer (README.md's table says the same; input.cpp and rover_control.cpp act on them).
constexpr std::pair<const char*, const char*> kKeys[] = {
    {"F1 or ?", "show / hide this list"},
    {"mouse, right button held", "look around (or left button outside the panel)"},
    {"W A S D, Q / E", "fly forward / left / back / right, down / up"},
    {"Shift", "fly 4x faster"},
    {"mouse wheel", "fly speed (x1.25 per notch)"},
    {"F", "drive the rover / back to flying"},
    {"arrow keys", "drive: Up forward, Down brake and reverse, Left / Right steer"},
    {"Space, N", "pause the simulation tick, advance one tick"},
    {"1 ... 5", "overlays: LOD colours, active fields, updated plants, cluster bounds, colliders"},
    {"M", "4x MSAA on / off"},
    {"F12 or P", "screenshot (EXR colour, EXR depth, PNG)"},
    {"R", "reload the scene"},
    {"H", "hide / show the panel"},
    {"Esc", "quit"},
};

// The keys window, centred over the view and at most as large as it (it scrolls in a small window).
void keysWindow(bool& open) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowSizeConstraints(ImVec2(0, 0), ImVec2(display.x - 16.0f, display.y - 16.0f));
    ImGui::SetNextWindowBgAlpha(1.0f);
    ImGui::PushStyleVar(ImGuiStyleVar_Alpha, 1.0f); // opaque over the panel: the list must read clearly
    if (ImGui::Begin("keys (F1 or ?)", &open, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse) &&
        ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
        for (const auto& [keys, action] : kKeys) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(keys);
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(action);
        }
        ImGui::EndTable();
    }
    ImGui::End();
    ImGui::PopStyleVar();
}

} // namespace

Ui::Ui(Context& ctx, GLFWwindow* window, const Swapchain& swapchain) : ctx_(ctx), format_(swapchain.format()) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr; // no imgui.ini next to the user's files
    ImGui::StyleColorsDark();
    ImGui::GetStyle().Alpha = 0.92f;

    // The backend allocates one descriptor set (the font atlas).
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4};
    VkDescriptorPoolCreateInfo poolInfo{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
        .flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT,
        .maxSets = 4,
        .poolSizeCount = 1,
        .pPoolSizes = &size,
    };
    VK_CHECK(vkCreateDescriptorPool(ctx.vk(), &poolInfo, nullptr, &pool_));

    VkAttachmentDescription attachment{
        .format = format_,
        .samples = VK_SAMPLE_COUNT_1_BIT,
        .loadOp = VK_ATTACHMENT_LOAD_OP_LOAD, // the tonemapped scene is already there
        .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
        .stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
        .stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
        .initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
        .finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
    };
    VkAttachmentReference reference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{
        .pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS,
        .colorAttachmentCount = 1,
        .pColorAttachments = &reference,
    };
    // The present pass wrote the image as a colour attachment just before; the panel blends over it.
    VkSubpassDependency dependency{
        .srcSubpass = VK_SUBPASS_EXTERNAL,
        .dstSubpass = 0,
        .srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
        .dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
        .srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
    };
    VkRenderPassCreateInfo passInfo{
        .sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO,
        .attachmentCount = 1,
        .pAttachments = &attachment,
        .subpassCount = 1,
        .pSubpasses = &subpass,
        .dependencyCount = 1,
        .pDependencies = &dependency,
    };
    VK_CHECK(vkCreateRenderPass(ctx.vk(), &passInfo, nullptr, &renderPass_));

    ImGui_ImplGlfw_InitForVulkan(window, true); // chains the viewer's GLFW callbacks installed before
    // Vertex buffers are kept per "image"; at least 3 so a buffer is only rewritten after its frame completed
    // (the viewer keeps 2 frames in flight).
    uint32_t images = std::max(swapchain.imageCount(), 3u);
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = ctx.device.instance();
    info.PhysicalDevice = ctx.device.physical();
    info.Device = ctx.vk();
    info.QueueFamily = ctx.device.queueFamily();
    info.Queue = ctx.device.queue();
    info.DescriptorPool = pool_;
    info.MinImageCount = images;
    info.ImageCount = images;
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = checkImguiVk;
    require(ImGui_ImplVulkan_Init(&info, renderPass_), "Dear ImGui's Vulkan backend failed to initialise");
    ctx.submitter.immediate([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
}

Ui::~Ui() {
    ctx_.submitter.waitIdle();
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    destroyFramebuffers();
    vkDestroyRenderPass(ctx_.vk(), renderPass_, nullptr);
    vkDestroyDescriptorPool(ctx_.vk(), pool_, nullptr);
}

bool Ui::wantsMouse() const {
    return ImGui::GetIO().WantCaptureMouse;
}
bool Ui::wantsKeyboard() const {
    return ImGui::GetIO().WantCaptureKeyboard;
}

void Ui::destroyFramebuffers() {
    for (VkFramebuffer f : framebuffers_) vkDestroyFramebuffer(ctx_.vk(), f, nullptr);
    framebuffers_.clear();
}

void Ui::createFramebuffers(const Swapchain& swapchain) {
    require(swapchain.format() == format_, "the window's surface format changed; restart the viewer");
    // The swapchain was just recreated after the GPU drained (Swapchain::acquire), so the old ones are unused.
    destroyFramebuffers();
    extent_ = swapchain.extent();
    for (uint32_t i = 0; i < swapchain.imageCount(); ++i) {
        VkImageView view = swapchain.view(i);
        VkFramebufferCreateInfo info{
            .sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO,
            .renderPass = renderPass_,
            .attachmentCount = 1,
            .pAttachments = &view,
            .width = extent_.width,
            .height = extent_.height,
            .layers = 1,
        };
        VkFramebuffer framebuffer;
        VK_CHECK(vkCreateFramebuffer(ctx_.vk(), &info, nullptr, &framebuffer));
        framebuffers_.push_back(framebuffer);
    }
    generation_ = swapchain.generation();
}

void Ui::panel(PanelState& s) {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(330, 0), ImGuiCond_FirstUseEver);
    // A small window (tests, thumbnails) would be mostly panel: start with it folded to its title bar.
    ImGui::SetNextWindowCollapsed(ImGui::GetIO().DisplaySize.x < 640.0f, ImGuiCond_FirstUseEver);
    ImGui::Begin("sward-view");
    ImGui::Text("%s", s.scene.c_str());
    ImGui::TextDisabled("%s", s.device.c_str());

    if (!s.frameTimes.empty()) {
        float last = s.frameTimes.back();
        float top = *std::max_element(s.frameTimes.begin(), s.frameTimes.end());
        char label[64];
        std::snprintf(label, sizeof label, "%.1f ms (%.0f fps)", last, last > 0 ? 1000.0f / last : 0.0f);
        ImGui::PlotLines("##frame", s.frameTimes.data(), int(s.frameTimes.size()), 0, label, 0.0f, top * 1.1f,
                         ImVec2(-1, 50));
    }
    if (ImGui::CollapsingHeader("GPU passes", ImGuiTreeNodeFlags_DefaultOpen)) {
        double total = 0.0;
        for (auto& [name, ms] : s.passTimes) {
            ImGui::Text("%-12s %7.2f ms", name.c_str(), ms);
            total += ms;
        }
        ImGui::Text("%-12s %7.2f ms", "total", total);
    }
    if (s.worldTiles > 0 && ImGui::CollapsingHeader("World", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::Text("resident tiles %u, generating %u", s.worldTiles, s.worldPending);
        ImGui::Text("memory %.0f / %.0f MiB", s.worldMiB, s.worldBudgetMiB);
        ImGui::Text("generated %llu, evicted %llu", (unsigned long long)s.worldGenerated,
                    (unsigned long long)s.worldEvicted);
    }
    if (ImGui::CollapsingHeader("Simulation", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::Text("tick %llu  (%.2f s)%s", (unsigned long long)s.tick, s.simulationSeconds,
                    s.paused ? "  paused" : "");
        ImGui::Text("active fields %zu / %zu, contacts %zu", s.activeFieldCount, s.fieldCount, s.contacts);
        ImGui::Text("collision pass %.2f ms", s.collisionMs);
        ImGui::Checkbox("pause (Space)", &s.paused);
        ImGui::SameLine();
        s.step |= ImGui::Button("step (N)");
        s.toggleDrive |= ImGui::Button(s.driving ? "fly (F)" : "drive rover (F)");
    }
    if (ImGui::CollapsingHeader("Wind", ImGuiTreeNodeFlags_DefaultOpen)) {
        float direction = float(s.wind.directionDegrees);
        if (ImGui::SliderFloat("direction", &direction, 0.0f, 360.0f, "%.0f deg")) s.wind.directionDegrees = direction;
        ImGui::SliderFloat("strength", &s.wind.strength, 0.0f, 0.6f);
        ImGui::SliderFloat("gusts", &s.wind.gustStrength, 0.0f, 0.6f);
        ImGui::SliderFloat("gust frequency", &s.wind.gustFrequency, 0.0f, 2.0f, "%.2f Hz");
        ImGui::SliderFloat("flutter", &s.wind.flutter, 0.0f, 0.2f);
    }
    if (ImGui::CollapsingHeader("Vegetation", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::SliderFloat("density", &s.density, 0.05f, 2.0f, "x %.2f");
        ImGui::SameLine();
        s.applyDensity |= ImGui::Button("apply");
        ImGui::SliderFloat("near -> mid", &s.lod.nearToMid, 1.0f, 100.0f, "%.0f m");
        ImGui::SliderFloat("mid -> far", &s.lod.midToFar, 1.0f, 300.0f, "%.0f m");
        ImGui::SliderFloat("far limit", &s.lod.farLimit, 1.0f, 600.0f, "%.0f m");
        s.lod.midToFar = std::max(s.lod.midToFar, s.lod.nearToMid);
        s.lod.farLimit = std::max(s.lod.farLimit, s.lod.midToFar);
    }
    if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::Checkbox("4x MSAA", &s.msaa);
        ImGui::SliderFloat("exposure", &s.exposure, 0.05f, 4.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
        ImGui::Checkbox("LOD colours (1)", &s.lodColors);
        ImGui::Checkbox("active fields (2)", &s.activeFields);
        ImGui::Checkbox("updated plants (3)", &s.updatedPlants);
        ImGui::Checkbox("cluster bounds (4)", &s.clusterBounds);
        ImGui::Checkbox("colliders (5)", &s.colliders);
        ImGui::Text("camera speed %.1f m/s (wheel)", s.cameraSpeed);
        s.screenshot |= ImGui::Button("screenshot (F12)");
        ImGui::SameLine();
        s.reload |= ImGui::Button("reload scene (R)");
    }
    if (!s.message.empty()) ImGui::TextWrapped("%s", s.message.c_str());
    s.keysHelp ^= ImGui::Button("keys (F1)");
    ImGui::End();
    if (s.keysHelp) keysWindow(s.keysHelp);
    ImGui::Render();
}

void Ui::record(VkCommandBuffer cmd, const Swapchain& swapchain, uint32_t imageIndex) {
    if (generation_ != swapchain.generation()) createFramebuffers(swapchain);
    VkRenderPassBeginInfo begin{
        .sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO,
        .renderPass = renderPass_,
        .framebuffer = framebuffers_[imageIndex],
        .renderArea = {{0, 0}, extent_},
    };
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
    vkCmdEndRenderPass(cmd);
}

} // namespace sward

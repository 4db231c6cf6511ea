// OffscreenFrame and renderFrame (declared in render/scene_renderer.h): frames rendered into targets of their own
// and read back to host images.
#include "render/scene_renderer.h"

#include "common/half_float.h"
#include "engine/barriers.h"
#include "shared/gpu_layout.h"

#include <cstring>

namespace sward {

OffscreenFrame::OffscreenFrame(Context& ctx, uint32_t width, uint32_t height, uint32_t samples, bool flow)
    : ctx_(ctx), main_(ctx, mainPassTargetDesc(width, height, samples)),
      truth_(ctx, truthPassTargetDesc(width, height, flow)) {
    uint64_t pixels = uint64_t(width) * height;
    color_ = createBuffer(ctx, pixels * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::Readback);
    depth_ = createBuffer(ctx, pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::Readback);
    labels_ = createBuffer(ctx, pixels * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::Readback);
    normals_ = createBuffer(ctx, pixels * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::Readback);
    if (flow)
        for (Buffer& b : flow_)
            b = createBuffer(ctx, pixels * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::Readback);
}

namespace {

// The truth pass's (label, tile) pairs: labels always, the tile labels for a world of several tiles.
void splitLabels(const Buffer& pairs, uint64_t pixels, bool world, std::vector<uint32_t>& labels,
                 std::vector<uint32_t>* tiles) {
    const uint32_t* pair = reinterpret_cast<const uint32_t*>(pairs.mapped());
    labels.resize(pixels);
    for (uint64_t i = 0; i < pixels; ++i) labels[i] = pair[2 * i];
    if (!world || !tiles) return;
    tiles->resize(pixels);
    for (uint64_t i = 0; i < pixels; ++i) (*tiles)[i] = pair[2 * i + 1];
}

std::vector<uint16_t> halves(const Buffer& buffer, uint64_t count) {
    std::vector<uint16_t> out(count);
    std::memcpy(out.data(), buffer.mapped(), count * sizeof(uint16_t));
    return out;
}

std::vector<float> floats(const Buffer& buffer, uint64_t count) {
    std::vector<float> out(count);
    std::memcpy(out.data(), buffer.mapped(), count * sizeof(float));
    return out;
}

// The truth pass's normals without their unused w.
std::vector<float> normalsXyz(const Buffer& xyzw, uint64_t pixels) {
    const float* normal = reinterpret_cast<const float*>(xyzw.mapped());
    std::vector<float> xyz(pixels * 3);
    for (uint64_t i = 0; i < pixels; ++i)
        for (uint64_t c = 0; c < 3; ++c) xyz[3 * i + c] = normal[4 * i + c];
    return xyz;
}

} // namespace

OffscreenFrame::~OffscreenFrame() {
    for (Buffer* b : {&color_, &depth_, &labels_, &normals_, &rightColor_, &rightDepth_, &rightLabels_, &rightNormals_,
                      &flow_[0], &flow_[1], &rightFlow_[0], &rightFlow_[1]})
        retireBuffer(ctx_, *b);
}

void OffscreenFrame::createRightTargets() {
    const RenderTargetDesc& desc = main_.desc();
    const uint64_t pixels = uint64_t(desc.width) * desc.height;
    rightMain_ = std::make_unique<RenderTarget>(ctx_, desc);
    rightTruth_ = std::make_unique<RenderTarget>(ctx_, truth_.desc());
    rightColor_ = createBuffer(ctx_, pixels * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::Readback);
    rightDepth_ = createBuffer(ctx_, pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::Readback);
    rightLabels_ = createBuffer(ctx_, pixels * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::Readback);
    rightNormals_ = createBuffer(ctx_, pixels * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::Readback);
    if (flow_[0])
        for (Buffer& b : rightFlow_)
            b = createBuffer(ctx_, pixels * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryIntent::Readback);
}

void OffscreenFrame::renderColour(SceneRenderer& renderer, const Camera& camera, double timeSeconds,
                                  uint32_t frameIndex, const std::function<void(VkCommandBuffer)>& prologue,
                                  const Camera* right, std::vector<uint16_t>& left, std::vector<uint16_t>* rightRgba) {
    const RenderTargetDesc& desc = main_.desc();
    require(camera.width == desc.width && camera.height == desc.height, "camera and frame sizes differ");
    require(!right || (rightRgba && right->width == desc.width && right->height == desc.height),
            "left and right sizes differ");
    require(renderer.samples() == uint32_t(desc.samples), "renderer and frame sample counts differ");
    if (right && !rightMain_) createRightTargets();
    ctx_.submitter.immediate([&](VkCommandBuffer cmd) {
        if (prologue) prologue(cmd);
        SceneRenderer::View views[2] = {{&camera, &main_, nullptr}, {right, rightMain_.get(), nullptr}};
        renderer.recordViews(cmd, {views, right ? 2u : 1u}, timeSeconds, frameIndex);
        main_.recordReadback(cmd, 0, color_);
        if (right) rightMain_->recordReadback(cmd, 0, rightColor_);
        transferToHostBarrier(cmd);
    });
    const uint64_t values = uint64_t(desc.width) * desc.height * 4;
    left = halves(color_, values);
    if (right) *rightRgba = halves(rightColor_, values);
}

FrameImages OffscreenFrame::render(SceneRenderer& renderer, const Camera& camera, double timeSeconds,
                                   uint32_t frameIndex, const std::function<void(VkCommandBuffer)>& prologue,
                                   const Camera* right, const FlowTicks* flow, bool colour) {
    const RenderTargetDesc& desc = main_.desc();
    require(camera.width == desc.width && camera.height == desc.height, "camera and frame sizes differ");
    require(!right || (right->width == desc.width && right->height == desc.height), "left and right sizes differ");
    require(renderer.samples() == uint32_t(desc.samples), "renderer and frame sample counts differ");
    const uint64_t pixels = uint64_t(desc.width) * desc.height;
    require(!flow || flow_[0], "OffscreenFrame::render: flow needs a frame made with flow");
    if (right && !rightMain_) createRightTargets();
    ctx_.submitter.immediate([&](VkCommandBuffer cmd) {
        if (prologue) prologue(cmd);
        SceneRenderer::View views[2] = {{&camera, colour ? &main_ : nullptr, &truth_},
                                        {right, colour ? rightMain_.get() : nullptr, rightTruth_.get()}};
        renderer.recordViews(cmd, {views, right ? 2u : 1u}, timeSeconds, frameIndex, nullptr, true, flow);
        if (colour) main_.recordReadback(cmd, 0, color_);
        truth_.recordReadback(cmd, 0, depth_);
        truth_.recordReadback(cmd, 1, labels_);
        truth_.recordReadback(cmd, 2, normals_);
        if (right) {
            if (colour) rightMain_->recordReadback(cmd, 0, rightColor_);
            rightTruth_->recordReadback(cmd, 0, rightDepth_);
            rightTruth_->recordReadback(cmd, 1, rightLabels_);
            rightTruth_->recordReadback(cmd, 2, rightNormals_);
        }
        for (uint32_t d = 0; flow && d < 2; ++d) {
            truth_.recordReadback(cmd, 3 + d, flow_[d]);
            if (right) rightTruth_->recordReadback(cmd, 3 + d, rightFlow_[d]);
        }
        transferToHostBarrier(cmd);
    });
    FrameImages images{.width = desc.width, .height = desc.height};
    if (colour) images.rgbaHalf = halves(color_, pixels * 4);
    images.depth.resize(pixels);
    std::memcpy(images.depth.data(), depth_.mapped(), pixels * 4); // float bit patterns written by the shader
    splitLabels(labels_, pixels, renderer.world(), images.labels, &images.tiles);
    images.normals = normalsXyz(normals_, pixels);
    if (right) {
        if (colour) images.rightRgbaHalf = halves(rightColor_, pixels * 4);
        images.rightDepth.resize(pixels);
        std::memcpy(images.rightDepth.data(), rightDepth_.mapped(), pixels * 4);
        splitLabels(rightLabels_, pixels, false, images.rightLabels, nullptr);
        images.rightNormals = normalsXyz(rightNormals_, pixels);
    }
    if (flow) {
        images.flowForward = floats(flow_[0], pixels * 4);
        images.flowBackward = floats(flow_[1], pixels * 4);
        if (right) {
            images.rightFlowForward = floats(rightFlow_[0], pixels * 4);
            images.rightFlowBackward = floats(rightFlow_[1], pixels * 4);
        }
    }
    return images;
}

FrameImages renderFrame(Context& ctx, SceneRenderer& renderer, const Camera& camera, double timeSeconds) {
    OffscreenFrame frame(ctx, camera.width, camera.height, renderer.samples());
    return frame.render(renderer, camera, timeSeconds, 0);
}

} // namespace sward

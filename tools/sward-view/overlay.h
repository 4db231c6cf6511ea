// Overlay: the viewer's debug lines, drawn into the main HDR pass with the scene's depth (no depth writes):
// grass-field rectangles coloured by interaction activity (paper Figure 7), plant-cluster bounds and collider
// wireframes. Lines are rebuilt on the CPU each frame and streamed through a host-visible ring (one range
// per frame in flight), so nothing waits.
#pragma once

#include "interaction/colliders.h"
#include "engine/context.h"
#include "engine/pipelines.h"
#include "engine/resources.h"
#include "shared/config.h"
#include "shared/gpu_layout.h"

#include <glm/glm.hpp>

#include <vector>

namespace sward {

class Ground;
struct VegetationTile;

class Overlay {
public:
    Overlay(Context& ctx, VkSampleCountFlagBits samples);
    ~Overlay();
    Overlay(const Overlay&) = delete;
    Overlay& operator=(const Overlay&) = delete;

    void clear() { vertices_.clear(); }
    void line(glm::vec3 a, glm::vec3 b, glm::vec3 color);
    void box(glm::vec3 lo, glm::vec3 hi, glm::vec3 color);
    // Field outlines draped over the terrain `lift` metres up, within `radius` of `eye`: active fields bright
    // orange, the others dim blue.
    void fields(const VegetationTile& tile, const Ground& terrain, const std::vector<uint8_t>& active,
                glm::vec3 eye, float radius, float lift);
    // Bounding boxes of the non-empty clusters within `radius` of `eye`.
    void clusters(const VegetationTile& tile, glm::vec3 eye, float radius);
    void collider(const Collider& c, glm::vec3 color);

    // Copies this frame's lines into ring slot `slot`; call before the main pass is recorded.
    void upload(uint32_t slot);
    // Records the draw into the current main pass (SceneRenderer's overlay hook).
    void draw(VkCommandBuffer cmd, const DescriptorBinding& frame, uint32_t slot);
    size_t lineCount() const { return vertices_.size() / 2; }

    static constexpr uint32_t kSlots = gpu::kFrameDataSlots; // line buffers written per frame (shaders/shared/config.h)

private:
    Context& ctx_;
    Pipeline pipeline_;
    std::vector<gpu::DebugLineVertex> vertices_;
    Buffer buffers_[kSlots];
    uint32_t counts_[kSlots] = {};
};

} // namespace sward

#include "overlay.h"

#include "world/ground.h"
#include "vegetation/vegetation_tile.h"

#include <cmath>
#include <cstring>

namespace sward {

Overlay::Overlay(Context& ctx, VkSampleCountFlagBits samples) : ctx_(ctx) {
    pipeline_ = createGraphicsPipeline(
        ctx.device,
        {.vertexShader = "debug_lines.vert",
         .fragmentShader = "debug_lines.frag",
         .vertexBindings = {{0, sizeof(gpu::DebugLineVertex), VK_VERTEX_INPUT_RATE_VERTEX}},
         .vertexAttributes = {{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(gpu::DebugLineVertex, position)},
                              {1, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(gpu::DebugLineVertex, color)}},
         .topology = VK_PRIMITIVE_TOPOLOGY_LINE_LIST,
         .cullMode = VK_CULL_MODE_NONE,
         .colorFormats = {VK_FORMAT_R16G16B16A16_SFLOAT},
         .depthFormat = VK_FORMAT_D32_SFLOAT,
         .depthTest = true,
         .depthWrite = false, // lines never hide each other or later geometry
         .depthCompare = VK_COMPARE_OP_GREATER_OR_EQUAL,
         .samples = samples},
        {.bindings = {layoutBinding(gpu::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_VERTEX_BIT)}});
}

Overlay::~Overlay() {
    ctx_.submitter.waitIdle();
    for (Buffer& b : buffers_)
        if (b) destroyBuffer(ctx_, b);
    destroyPipeline(ctx_.device, pipeline_);
}

void Overlay::line(glm::vec3 a, glm::vec3 b, glm::vec3 color) {
    vertices_.push_back({glm::vec4(a, 1.0f), glm::vec4(color, 1.0f)});
    vertices_.push_back({glm::vec4(b, 1.0f), glm::vec4(color, 1.0f)});
}

void Overlay::box(glm::vec3 lo, glm::vec3 hi, glm::vec3 color) {
    glm::vec3 c[8];
    for (int i = 0; i < 8; ++i) c[i] = glm::vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    const int edges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    for (auto& e : edges) line(c[e[0]], c[e[1]], color);
}

void Overlay::fields(const VegetationTile& tile, const Ground& terrain, const std::vector<uint8_t>& active,
                     glm::vec3 eye, float radius, float lift) {
    const glm::vec3 activeColor(6.0f, 1.6f, 0.1f), idleColor(0.3f, 0.6f, 2.0f);
    const int steps = std::max(1, int(tile.fieldSize / 2.5f)); // drape the edges over the terrain every ~2.5 m
    auto ground = [&](glm::vec2 p) { return glm::vec3(p, terrain.height(p) + lift); };
    for (size_t f = 0; f < tile.fields.size(); ++f) {
        const FieldVegetation& field = tile.fields[f];
        glm::vec2 lo = field.origin, hi = lo + glm::vec2(tile.fieldSize);
        glm::vec2 centre = 0.5f * (lo + hi);
        if (glm::length(centre - glm::vec2(eye)) > radius + tile.fieldSize) continue;
        bool on = f < active.size() && active[f];
        // Inset active fields slightly so the shared edge with an idle neighbour shows both colours.
        glm::vec2 inset = glm::vec2(on ? 0.3f : 0.0f);
        glm::vec2 a = lo + inset, b = hi - inset;
        glm::vec2 corners[5] = {a, {b.x, a.y}, b, {a.x, b.y}, a};
        for (int e = 0; e < 4; ++e)
            for (int s = 0; s < steps; ++s) {
                glm::vec2 p0 = glm::mix(corners[e], corners[e + 1], float(s) / float(steps));
                glm::vec2 p1 = glm::mix(corners[e], corners[e + 1], float(s + 1) / float(steps));
                line(ground(p0), ground(p1), on ? activeColor : idleColor);
            }
    }
}

void Overlay::clusters(const VegetationTile& tile, glm::vec3 eye, float radius) {
    const glm::vec3 color(0.2f, 2.0f, 0.6f);
    for (const FieldVegetation& field : tile.fields) {
        if (glm::length(0.5f * (field.boundsMin + field.boundsMax) - eye) > radius + tile.fieldSize) continue;
        for (const gpu::PlantCluster& c : field.clusters) {
            if (c.range.y == 0) continue;
            glm::vec3 lo(c.boundsMin), hi(c.boundsMax);
            if (glm::length(0.5f * (lo + hi) - eye) > radius) continue;
            box(lo, hi, color);
        }
    }
}

namespace {

// Unit vectors u, v perpendicular to unit n.
void basis(glm::vec3 n, glm::vec3& u, glm::vec3& v) {
    glm::vec3 a = std::abs(n.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
    u = glm::normalize(glm::cross(n, a));
    v = glm::cross(n, u);
}

} // namespace

void Overlay::collider(const Collider& c, glm::vec3 color) {
    constexpr int kSegments = 24;
    auto circle = [&](glm::vec3 centre, glm::vec3 u, glm::vec3 v, float r) {
        for (int i = 0; i < kSegments; ++i) {
            float a0 = 6.2831853f * float(i) / kSegments, a1 = 6.2831853f * float(i + 1) / kSegments;
            line(centre + r * (std::cos(a0) * u + std::sin(a0) * v), centre + r * (std::cos(a1) * u + std::sin(a1) * v),
                 color);
        }
    };
    switch (c.shape) {
    case ColliderShape::Sphere:
        circle(c.centre, {1, 0, 0}, {0, 1, 0}, c.radius);
        circle(c.centre, {1, 0, 0}, {0, 0, 1}, c.radius);
        circle(c.centre, {0, 1, 0}, {0, 0, 1}, c.radius);
        break;
    case ColliderShape::Capsule: {
        glm::vec3 axis = c.end - c.centre;
        glm::vec3 n = glm::length(axis) > 1e-6f ? glm::normalize(axis) : glm::vec3(0, 0, 1), u, v;
        basis(n, u, v);
        circle(c.centre, u, v, c.radius); // the rims at both ends of the segment
        circle(c.end, u, v, c.radius);
        circle(0.5f * (c.centre + c.end), n, u, c.radius + 0.5f * glm::length(axis)); // outline across the axis
        for (glm::vec3 d : {u, -u, v, -v}) line(c.centre + d * c.radius, c.end + d * c.radius, color);
        break;
    }
    case ColliderShape::Box: {
        glm::vec3 h = c.halfExtents;
        glm::vec3 p[8];
        for (int i = 0; i < 8; ++i)
            p[i] = c.centre + c.rotation * glm::vec3(i & 1 ? h.x : -h.x, i & 2 ? h.y : -h.y, i & 4 ? h.z : -h.z);
        const int edges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
        for (auto& e : edges) line(p[e[0]], p[e[1]], color);
        break;
    }
    }
}

void Overlay::upload(uint32_t slot) {
    slot %= kSlots;
    uint64_t bytes = vertices_.size() * sizeof(gpu::DebugLineVertex);
    counts_[slot] = uint32_t(vertices_.size());
    if (bytes == 0) return;
    Buffer& buffer = buffers_[slot];
    if (!buffer || buffer.size < bytes) {
        if (buffer) retireBuffer(ctx_, buffer); // a frame in flight may still read it
        buffer = createBuffer(ctx_, std::max<uint64_t>(bytes * 2, 64 << 10), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                              MemoryIntent::Upload);
    }
    std::memcpy(buffer.mapped(), vertices_.data(), bytes);
}

void Overlay::draw(VkCommandBuffer cmd, const DescriptorBinding& frame, uint32_t slot) {
    slot %= kSlots;
    if (counts_[slot] == 0) return;
    bindPipeline(cmd, pipeline_);
    pushDescriptors(ctx_.device, cmd, pipeline_, {frame});
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &buffers_[slot].handle, &offset);
    vkCmdDraw(cmd, counts_[slot], 1, 0, 0);
}

} // namespace sward

// A small uniform-grass tile and a CPU-only interaction simulation, shared by the interaction tests.
#pragma once

#include "interaction/interaction.h"
#include "vegetation/placement.h"
#include "vegetation/records.h"

#include <cstring>
#include <span>
#include <vector>

namespace sward::test {

constexpr uint32_t kGrass = 1;

// Flat ground at z = 0 with uniform grass (16 plants/m^2) over a square tile of `size` metres.
inline VegetationParams tileParams(float size) {
    VegetationParams p;
    p.tileSize = size;
    p.seed = 3;
    return p;
}

inline VegetationTile makeTile(float size) {
    const uint32_t n = uint32_t(size / 2.0f) + 1;
    Ground ground(Heightfield(n, n, 2.0f, glm::vec2(0.0f), std::vector<float>(size_t(n) * n, 0.0f)));
    GrassMap grass(1, 1, 3, {0.0f, 1.0f, 0.0f}, "uniform grass");
    return generateTile(ground, grass, tileParams(size), {}, 2);
}

// 50 x 50 m: 2 x 2 fields, about 40,000 plants.
inline const VegetationTile& smallTile() {
    static const VegetationTile tile = makeTile(50.0f);
    return tile;
}

struct PlantInfo {
    glm::vec3 base;
    float height;
    uint32_t field;
};

inline std::vector<PlantInfo> plantInfos(const VegetationTile& tile, const VegetationParams& params) {
    std::vector<PlantInfo> out;
    for (uint32_t f = 0; f < tile.fields.size(); ++f) {
        const FieldVegetation& field = tile.fields[f];
        for (const gpu::PlantStatic& r : field.staticRecords) {
            PlantInstance p = decodePlantStatic(r);
            out.push_back({decodePlantPosition(r, field.origin, field.positionStep),
                           params.categories[p.category].height * float(p.size) / gpu::kPlantSizeDivisor, f});
        }
    }
    return out;
}

inline glm::vec2 pushOf(const gpu::PlantContact& c) {
    return {float(int16_t(c.push & 0xffffu)) / 32767.0f, float(int16_t(c.push >> 16)) / 32767.0f};
}

inline bool sameBytes(const auto& a, const auto& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
}
inline bool sameBytes(const TickContacts& a, const TickContacts& b) {
    return sameBytes(a.flatten(), b.flatten());
}

// A world plus the CPU stand-in for the GPU's dynamic buffer.
struct Sim {
    const VegetationTile* tile;
    InteractionWorld world;
    std::vector<gpu::PlantDynamic> dynamics;
    TickResult step(std::span<const Collider> colliders) {
        TickResult r = world.step(colliders);
        simulateOnCpu(dynamics, r, r.activeFields, *tile, world.params().recovery);
        return r;
    }
};

inline Sim makeSim(const VegetationTile& tile, const InteractionParams& params = {}, uint32_t threads = 1) {
    InteractionWorld world(tile, tileParams(tile.size), params, threads);
    auto dynamics = world.initialDynamics();
    return Sim{&tile, std::move(world), std::move(dynamics)};
}

// A sphere rolling along +x at y through the small tile's field 0 and 1, one position per tick.
inline Collider sphereAt(uint32_t tick, float force = 0.4f) {
    return makeSphere(7, {4.0f + 0.25f * float(tick), 12.0f, 0.3f}, 0.6f, force);
}

} // namespace sward::test

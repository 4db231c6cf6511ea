// A scene built from JSON with its ground, vegetation tile and atlas, and typed GPU buffer read-back: shared by the
// tests that compare the GPU expansion (cards and blades) with the CPU reference.
#pragma once

#include "engine/resources.h"
#include "render/scene_renderer.h"
#include "scene/scene.h"

#include <nlohmann/json.hpp>

#include <cstring>
#include <string>
#include <vector>

namespace sward::test {

struct SceneSetup {
    Scene scene;
    Ground terrain;
    VegetationTile tile;
    Atlas atlas;
    SceneSetup(const nlohmann::json& json, const std::string& name)
        : scene(parseScene(json, name)), terrain(buildTerrain(scene)), tile(buildVegetation(scene, terrain, 2)),
          atlas(buildAtlas(scene)) {}
    Camera camera(uint32_t width, uint32_t height) const { return sceneCamera(scene, terrain, width, height); }
};

// The first `count` elements of `buffer`.
template <typename T> std::vector<T> readAll(Context& ctx, const Buffer& buffer, uint32_t count) {
    std::vector<uint8_t> bytes = readBuffer(ctx, buffer, 0, uint64_t(count) * sizeof(T));
    std::vector<T> out(count);
    std::memcpy(out.data(), bytes.data(), bytes.size());
    return out;
}

} // namespace sward::test

// A flat square of uniform grass for the range tests: the scene, its ground, atlas and plants.
#pragma once

#include "scene/scene.h"
#include "scene/terrain.h"
#include "vegetation/placement.h"

#include <nlohmann/json.hpp>

#include <string>

namespace sward::test {

struct UniformPatch {
    Scene scene;
    Ground ground;
    Atlas atlas;
    VegetationTile tile;
};

// `density` grass plants per m^2 (0.5 m tall) on a flat `size` m square, no wind; `extra` merged into the scene JSON.
inline UniformPatch uniformPatch(double density, double size = 50.0, const nlohmann::json& extra = {}) {
    nlohmann::json j = {
        {"seed", 5},
        {"terrain", {{"size", size}, {"spacing", 1.0}, {"amplitude", 0.0}}},
        {"wind", {{"strength", 0.0}, {"gust_strength", 0.0}, {"flutter", 0.0}}},
        {"vegetation",
         {{"categories",
           {{{"name", "ferns"}, {"density", 0.0}, {"height", 0.5}},
            {{"name", "grass"}, {"density", density}, {"height", 0.5}, {"height_variation", 0.2}, {"variants", 8}},
            {{"name", "flowers"}, {"density", 0.0}, {"height", 0.5}}}}}}};
    if (!extra.is_null()) j.merge_patch(extra);
    UniformPatch p;
    p.scene = parseScene(j, "patch.json");
    p.ground = buildTerrain(p.scene);
    // The built-in atlas (the patch names none) does not depend on the scene: painted once per test process.
    static const Atlas builtIn = buildAtlas(p.scene);
    p.atlas = builtIn;
    const GrassMap map(1, 1, 3, {1.0f, 1.0f, 1.0f}, "uniform");
    p.tile = generateTile(p.ground, map, vegetationOn(p.scene, p.ground), TileCoord{0, 0}, 0);
    return p;
}

} // namespace sward::test

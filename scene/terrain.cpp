#include "scene/terrain.h"

#include "common/error.h"
#include "common/json_reader.h"
#include "scene/scene.h"
#include "scene/world_ground.h"
#include "world/gltf_mesh.h"

#include <cmath>

namespace sward {

namespace {

Heightfield loadHeightmap(const Scene& scene) {
    const HeightmapParams& h = scene.terrain.heightmap;
    try {
        return loadHeightfield(h.path, float(h.heightScale), float(h.metresPerPixel), glm::vec2(h.origin),
                               float(h.heightOffset), scene.assets.folders());
    } catch (const Error& e) {
        throw Error(scene.source + ": 'terrain.heightmap': " + e.what());
    }
}

Ground meshGround(const Scene& scene) {
    const TerrainParams& t = scene.terrain;
    TriangleMesh mesh;
    try {
        mesh = loadGltfMesh(t.meshPath, scene.assets);
    } catch (const Error& e) {
        throw Error(scene.source + ": 'terrain.mesh': " + e.what());
    }
    try {
        Ground ground(std::move(mesh), t.selection);
        if (ground.plantableTriangles() == 0)
            throw Error("no surface of it may carry vegetation (" +
                        std::string(t.selection.materials.empty() ? "every material" : "the 'vegetation_materials'") +
                        " at most 'max_slope_deg' " + formatNumber(t.selection.maxSlopeDegrees) + " steep)");
        return ground;
    } catch (const Error& e) {
        throw Error(scene.source + ": 'terrain.mesh' ('" + t.meshPath + "'): " + e.what());
    }
}

} // namespace

Ground buildTerrain(const Scene& scene) {
    // A world of one tile on a DEM: that tile's window of it, never the whole raster (it may be far larger).
    if (demWorld(scene)) {
        const glm::dvec2 origin(scene.vegetation.worldOrigin);
        return Ground(worldHeights(scene, origin, origin + double(scene.vegetation.tileSize)), scene.terrain.selection);
    }
    switch (scene.terrain.source) {
    case TerrainParams::Source::Heightmap:
        return Ground(loadHeightmap(scene), scene.terrain.selection);
    case TerrainParams::Source::Mesh:
        return meshGround(scene);
    case TerrainParams::Source::Procedural:
        break;
    }
    return Ground(makeProceduralTerrain(scene.terrain.procedural), scene.terrain.selection);
}

VegetationParams vegetationOn(const Scene& scene, const Ground& terrain) {
    VegetationParams params = scene.vegetation;
    if (scene.terrain.source == TerrainParams::Source::Procedural || demWorld(scene)) return params;
    if (!scene.vegetationOriginSet) params.worldOrigin = terrain.boundsMin();
    if (!scene.vegetationTileSet) {
        const glm::vec2 extent = terrain.boundsMax() - params.worldOrigin;
        const double fields = std::ceil(double(std::max(extent.x, extent.y)) / double(params.fieldSize));
        params.tileSize = float(std::max(fields, 1.0) * double(params.fieldSize));
    }
    validateVegetationParams(params, scene.source + " (the vegetation tile fitted to the ground's extent)");
    return params;
}

} // namespace sward

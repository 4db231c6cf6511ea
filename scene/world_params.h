// The scene's "world" object (docs/scene-format.md): a world of N x M scene tiles of procedural terrain and plants,
// generated around interest points under a memory budget (scene/world_tiles.h), and the bound that budget is checked
// against before anything is generated.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>

namespace sward {

class JsonReader;
struct Scene;

// Tiles per world side at most, and the world's extent per side: plant positions and field origins are floats, so
// 32 km keeps their error under 2 mm at the far edge.
inline constexpr uint32_t kMaxWorldTilesPerSide = 256;
inline constexpr double kMaxWorldExtent = 32768.0;
inline constexpr double kMaxLoadRadius = 10000.0, kMaxEvictRadius = 20000.0;

struct WorldParams {
    bool enabled = false;                              // the scene has a "world" object
    uint32_t tilesX = 1, tilesY = 1;                   // "tiles": [N, M], tile (x, y) for x < N, y < M
    double loadRadius = 300.0;                         // metres: tiles within it of an interest point are made resident
    double evictRadius = 400.0;                        // metres, > loadRadius (default loadRadius + 100): tiles
                                                       // beyond it of every point are evicted
    uint64_t memoryBudgetBytes = uint64_t(2048) << 20; // "memory_budget_mib": resident tiles at most
    double viewDistance = 300.0;                       // metres, <= loadRadius (default loadRadius): ground and
                                                       // plants are drawn out to it from the camera
    bool horizon = true;       // "horizon": beyond view_distance a coarse ring of the world's terrain is drawn
    double horizonSpacing = 0; // "horizon.spacing", metres (a whole multiple of terrain.spacing); 0: the default
};

// The horizon ring's lattice by default: the least whole multiple of terrain.spacing that gives at most this many
// cells along the world's longer side (a 8 km world of 2 m spacing: 32 m, 250 x 250 cells, 125,000 triangles).
inline constexpr uint32_t kDefaultHorizonCells = 256;

// The machine's physical memory in bytes (0 when the system cannot tell).
uint64_t physicalMemoryBytes();

// Reads "tiles", "load_radius", "evict_radius", "view_distance", "memory_budget_mib" and "horizon" (false, or an
// object with "spacing"); errors name the file and
// the JSON path. A budget above physicalMemoryBytes() is refused (never lowered: output never depends on the machine).
WorldParams parseWorldParams(JsonReader r);

// The horizon ring's lattice spacing in metres: world.horizon.spacing, else the kDefaultHorizonCells default.
double horizonSpacing(const Scene& scene);

// The world's requirements on the rest of the scene, checked once terrain and vegetation are parsed: the procedural
// terrain or a DEM (not 'terrain.mesh'), the procedural meadow (not 'grass_map' / 'land_cover'); procedural:
// 'vegetation.tile_size' = 'terrain.size', a whole number of 'terrain.spacing' per tile and in
// 'vegetation.world_origin'; a DEM: checkDemWorld (scene/world_ground.h); the extent, and checkWorldBudget. Throws
// sward::Error naming the keys.
void checkWorldScene(const Scene& scene);

// What drawing a world of several tiles needs besides (renderers, not the tile streaming itself): lod.far + half
// lod.band within view_distance; the features still refused there. Throws sward::Error naming the keys.
void checkWorldDrawable(const Scene& scene);

// Upper bound of one tile's resident bytes, the same parts WorldTile::bytes counts: terrain heights, plant records
// (static + dynamic) at full grass-map intensity plus one per cluster and category (count rounding), cluster records
// and field headers, and with `farCover` the tile's cover map (tiles that are drawn).
uint64_t predictedTileBytes(const Scene& scene, bool farCover = false);

// The most tiles of side tileSize a disc of `radius` metres can touch, wherever its centre lies (an upper bound: the
// centre is sampled on a 64 x 64 grid per tile and the radius widened by the sampling step), at most tilesX * tilesY.
uint32_t maxTilesWithin(double radius, double tileSize, uint32_t tilesX, uint32_t tilesY);

// Throws sward::Error naming 'world.memory_budget_mib', 'world.load_radius' and 'world.evict_radius' when the tiles
// that can be resident around ONE interest point (those within evict_radius of it) can exceed the budget.
void checkWorldBudget(const Scene& scene, bool farCover = false);

} // namespace sward

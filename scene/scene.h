// Scene description: what sward-render and sward-view load from a JSON scene file.
//
// Every field is optional and has a documented default (docs/scene-format.md); unknown keys are errors, so
// a typo never silently falls back to a default. All values are validated (type, finiteness, range) and
// errors name the file and the JSON path, e.g. "examples/meadow.json: 'terrain.amplitude' must be ...".
#pragma once

#include "interaction/collision.h"
#include "scene/camera_rig.h"
#include "scene/objects.h"
#include "scene/range_sensors.h"
#include "scene/terrain.h"
#include "scene/vehicles.h"
#include "scene/world_params.h"
#include "vegetation/atlas.h"
#include "vegetation/grass_map.h"
#include "vegetation/land_cover.h"
#include "vegetation/vegetation_params.h"
#include "vegetation/vegetation_tile.h"
#include "world/asset_policy.h"
#include "world/camera.h"
#include "world/ground.h"
#include "world/path.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace sward {

// A heightmap raster as the ground (terrain.heightmap). Samples sit on a regular grid, north up: the raster's top
// row is the northern edge, its bottom-left sample lies at `origin`.
struct HeightmapParams {
    std::string path;          // "file": 16-bit PNG, float EXR, or any single-band raster GDAL reads (GeoTIFF, ...)
    double metresPerPixel = 0; // sample spacing; 0 = the file's own georeferencing (GDAL rasters only)
    double heightScale = 1.0;  // PNG: metres at the full-scale value 65535; other formats: metres per unit
    double heightOffset = 0.0; // metres added to every height
    glm::dvec2 origin{0.0};    // world xy of the south-west sample
    // A world's DEM (scene/world_ground.h fitWorldToDem, from the raster's header): its samples and their spacing in
    // metres, the world's lattice. 0 outside a world.
    uint32_t columns = 0, rows = 0;
    double spacing = 0.0;
};

// "terrain": the ground plants stand on — the procedural heightfield (default), a heightmap or a glTF mesh.
struct TerrainParams {
    enum class Source { Procedural, Heightmap, Mesh };
    Source source = Source::Procedural;
    ProceduralTerrainParams procedural; // size, spacing, amplitude, feature_size, octaves (procedural only)
    HeightmapParams heightmap;
    std::string meshPath;      // terrain.mesh.file: .gltf / .glb, Y-up as exporters write it
    GroundSelection selection; // terrain.mesh.vegetation_materials, terrain.max_slope_deg
    uint32_t material = 0;     // terrain.material: the bare ground's preset, gpu::kGroundMaterial*
};

struct SunParams {
    double azimuthDegrees = 135.0;        // clockwise from north (+y) towards east (+x)
    double elevationDegrees = 40.0;       // above the horizon
    glm::vec3 radiance{3.2f, 3.0f, 2.7f}; // linear RGB, arbitrary HDR units
    glm::vec3 direction() const;          // unit vector towards the sun
};

// "sky": the physical model (world/sky.h, Preetham) from the sun and a turbidity, or a horizon-to-zenith gradient of
// given colours (the default when the scene gives "zenith" or "horizon"); both light the scene's ambient and colour
// the aerial perspective's haze (shaders/shared/atmosphere.glsl).
struct SkyParams {
    enum class Model { Physical, Gradient };
    Model model = Model::Physical;
    double turbidity = 3.0;                // physical: 2 very clear, 3 clear, 6 hazy
    double clouds = 0.0;                   // physical: cover of the procedural cumulus, 0 (none) .. 1 (overcast)
    double visibility = 20000.0;           // metres at which the haze hides a dark object (Koschmieder); 0: no haze
    glm::vec3 zenith{0.25f, 0.45f, 0.95f}; // gradient only
    glm::vec3 horizon{0.75f, 0.85f, 1.0f}; // gradient only
    glm::vec3 groundAmbient{0.12f, 0.11f, 0.08f};
};

struct CameraParams {
    glm::dvec3 position{250.0, 180.0, 0.0};
    // When set, position.z is replaced by terrain height at position.xy plus this value.
    double heightAboveGround = 1.6;
    bool useHeightAboveGround = true;
    glm::dvec3 lookAt{250.0, 260.0, 0.0};
    double lookAtHeightAboveGround = 0.0;
    bool lookAtUsesGround = true;
    double fovYDegrees = 60.0;
    // Optional moving camera: along `path`, looking `lookAhead` metres further along it at the ground plus
    // lookAtHeightAboveGround. Replaces position / look_at when present.
    bool hasPath = false;
    PathParams path;
    double lookAhead = 10.0;
    RigParams rig; // stereo baseline, intrinsics, mount, sensor (camera_rig.h)
};

// A fixed-step sequence (issue 7 renders datasets from it).
struct SequenceParams {
    uint32_t frames = 1;          // frames 0 .. frames-1, frame i at time i * timeStep
    double timeStep = 1.0 / 30.0; // seconds per frame and per simulation tick
};

struct RenderParams {
    uint32_t width = 1280, height = 720;
    uint32_t samples = 4;          // 1 or 4
    uint32_t shadowMapSize = 2048; // texels per edge; 0 disables sun shadows
    float shadowDistance = 60.0f;  // metres from the camera covered by the first (finest) shadow cascade
    uint32_t shadowCascades = 3;   // cascades up to lod.far + lod.band (world/sun_shadow.h); 1..kMaxShadowCascades
    bool flow = false;             // motion ground truth: optical flow of every pixel to the next and previous tick
};

struct Scene {
    std::string source = "<built-in>"; // file the scene came from, for messages
    std::string name = "default";
    uint64_t seed = 1;
    TerrainParams terrain;
    SunParams sun;
    SkyParams sky;
    CameraParams camera;
    RenderParams render;
    SequenceParams sequence;
    LodParams lod;
    WindParams wind;
    VegetationParams vegetation;                                 // "vegetation" object, see vegetation_params.h
    bool vegetationTileSet = false, vegetationOriginSet = false; // tile_size / world_origin given in the file
    InteractionParams interaction;     // "interaction" object, see collision.h (recovery time step = sequence's)
    ActorParams actors;                // "vehicles", "colliders", "gusts"
    std::vector<ObjectParams> objects; // "objects": glTF models on paths (vegetation/objects.h), object k = index k
    bool vegetationEnabled = true;     // false: bare ground (paired studies, --no-vegetation)
    std::string grassMapPath;          // "grass_map", resolved against the scene's folder; empty = procedural meadow
    LandCoverParams landCover;         // "land_cover" (scene/land_cover_params.h): file resolved likewise; empty = none
    std::string atlasPngPath, atlasJsonPath; // "atlas": {"png", "json"}; empty = the built-in procedural atlas
    AssetPolicy assets; // where the files it names may be read from (loadScene: the scene file's folder)
    WorldParams world;  // "world": many tiles around interest points (scene/world_tiles.h); off = one tile
    std::vector<RangeSensorParams> rangeSensors; // "range_sensors": LiDARs, laser scanners, ToF cameras (range/)
};

// Parses and validates a scene; `source` names it in error messages, and relative file paths are taken against
// its folder. Every file the scene names (objects' models and their buffers, grass_map, land_cover.file, atlas) must
// pass `assets` (default: unconfined); the check runs here, so a refused path fails before anything is loaded.
Scene parseScene(const nlohmann::json& json, const std::string& source, const AssetPolicy& assets = {});
// A program's change of the scene's "wind", "sun" or "sky" (`key`) between frames (the Python module's set_wind,
// set_sun, set_sky): the keys of `value` as a scene file holds them, read over the current values with a scene
// file's checks and messages ('source' names the call); the sky keeps its model unless `value` names one or gives
// colours. Throws sward::Error leaving the scene as it was.
void updateSceneSection(Scene& scene, const std::string& key, const nlohmann::json& value, const std::string& source);
// Reads and parses a scene file ("" = the built-in default scene); throws sward::Error naming the file for missing
// files and bad JSON. `seed`, when set, replaces the scene's seed before parsing, so every seed derived from it
// (terrain, plants, gusts, sensor noise) follows. A scene file's assets must resolve (symlinks followed) inside its
// folder or one of `allowedAssetDirs` (--allow-assets); the built-in scene is unconfined.
Scene loadScene(const std::string& path, std::optional<uint64_t> seed = {},
                const std::vector<std::string>& allowedAssetDirs = {});
// The scene's atlas with its coverage-preserving mip chain: the files it names, or the built-in procedural one.
Atlas buildAtlas(const Scene& scene);
// The scene's grass map over a tile of `tileSize` metres: the file it names, the one made from its land cover (in a
// world, the land cover's window over the world tile whose south-west corner is `origin`), or the procedural meadow
// (seeded by the scene seed) over the tile whose south-west corner is `origin`.
GrassMap buildGrassMap(const Scene& scene, float tileSize, glm::dvec2 origin = glm::dvec2(0.0));
// Places the scene's vegetation on its terrain (buildTerrain, vegetationOn; threads: 0 = all cores). Checks the
// memory budget first.
VegetationTile buildVegetation(const Scene& scene, const Ground& terrain, uint32_t threads = 0);
// The same on a grass map already built (buildGrassMap over vegetationOn's tile).
VegetationTile buildVegetation(const Scene& scene, const Ground& terrain, const GrassMap& map, uint32_t threads);
// The scene camera at the given resolution and simulation time, resolved against the terrain.
Camera sceneCamera(const Scene& scene, const Ground& terrain, uint32_t width, uint32_t height, double time = 0.0);

// Every collider acting on the vegetation during tick `tick` (at time tick * sequence.time_step): the scene's
// vehicles, free colliders and gusts (actorColliders) followed by the objects' node colliders (objectColliders).
std::vector<Collider> sceneColliders(const Scene& scene, const std::vector<ObjectModel>& models, const Ground& terrain,
                                     uint64_t tick);
// True when anything in the scene can touch the vegetation (the interaction simulation must run).
bool sceneHasColliders(const Scene& scene);
// True when a collider of the scene presses ruts into the ground (RutParams::depth > 0).
bool sceneMakesRuts(const Scene& scene);

// Largest image a command-line resolution may ask for: each side at most kMaxImageSide pixels and at most
// kMaxImagePixels pixels in all (8192x8192 or 16384x4096: several GiB of render targets and readback already).
inline constexpr uint32_t kMaxImageSide = 16384;
inline constexpr uint64_t kMaxImagePixels = uint64_t(1) << 26;
// Parses "WxH" (e.g. "1280x720", digits only); throws a clear error for anything else, a side outside
// 1..kMaxImageSide or more than kMaxImagePixels pixels.
void parseResolution(const std::string& text, uint32_t& width, uint32_t& height);

} // namespace sward

#include "scene/scene.h"
#include "scene/world_ground.h"
#include "scene/scene_input.h"

#include "common/error.h"
#include "common/json_reader.h"
#include "common/optional_components.h"
#include "common/parse_number.h"
#include "scene/land_cover_params.h"
#include "scene/scene_limits.h"
#include "shared/gpu_layout.h"
#include "shared/plant_blades.h"
#include "vegetation/placement.h"
#include "world/ground.h"
#include "world/heightfield.h"

#include <filesystem>

#include <cmath>
#include <fstream>
#include <numbers>

namespace sward {

namespace {

glm::vec3 toVec3(glm::dvec3 v) {
    return glm::vec3(v);
}

// Built-in scenes ("<built-in>") have no folder: the paths they name are used as given.
bool isFile(const std::string& source) {
    return source.find('<') == std::string::npos;
}

// Paths in a scene file are relative to the scene file's folder.
std::string sceneFolder(const std::string& source) {
    return isFile(source) ? std::filesystem::path(source).parent_path().string() : std::string();
}

// The file named under `key` ("" when absent), resolved against the scene's folder and checked against its asset
// policy.
std::string assetPath(JsonReader& r, const char* key, const Scene& scene) {
    const std::string path = r.string(key, "");
    return path.empty() ? path : scene.assets.resolve(path, sceneFolder(scene.source), r.source() + ": " + r.name(key));
}

void readProceduralTerrain(JsonReader& r, ProceduralTerrainParams& t) {
    t.size = r.numberF("size", t.size, 10.0, 4000.0);
    t.spacing = r.numberF("spacing", t.spacing, 0.1, 50.0);
    t.amplitude = r.numberF("amplitude", t.amplitude, 0.0, 1000.0);
    t.featureSize = r.numberF("feature_size", t.featureSize, 1.0, 10000.0);
    t.octaves = uint32_t(r.integer("octaves", t.octaves, 1, 8));
    // Priced as a heightmap is (world/heightfield.h): 8000 cells a side took 54 s and 10 GB for a 32x24 render.
    if (t.size / t.spacing > float(kMaxHeightfieldCells)) {
        const uint64_t samples =
            uint64_t(std::lround(t.size / t.spacing) + 1) * uint64_t(std::lround(t.size / t.spacing) + 1);
        r.fail(r.name("size") + " / " + r.name("spacing") + " exceeds " + std::to_string(kMaxHeightfieldCells) +
               " cells a side: its ground would take about " +
               std::to_string(samples * kHeightfieldBytesPerSample >> 20) + " MiB");
    }
}

void readHeightmap(JsonReader r, const Scene& scene, HeightmapParams& h) {
    h.path = assetPath(r, "file", scene);
    if (h.path.empty()) r.fail(r.name("file") + " is required (the heightmap raster)");
    // Refused before anything is read, rendered or written in a build without GDAL.
    if (heightfieldNeedsGdal(h.path)) requireComponent(Component::Gdal, r.source() + ": " + r.name("file"));
    h.metresPerPixel = r.number("metres_per_pixel", h.metresPerPixel, 0.0, 1e4);
    h.heightScale = r.number("height_scale", h.heightScale, -1e5, 1e5);
    h.heightOffset = r.number("height_offset", h.heightOffset, -1e5, 1e5);
    h.origin = r.vector<2>("origin", h.origin, -1e6, 1e6);
    r.finish();
}

void readGroundMesh(JsonReader r, const Scene& scene, TerrainParams& t) {
    t.meshPath = assetPath(r, "file", scene);
    if (t.meshPath.empty()) r.fail(r.name("file") + " is required (the glTF / GLB ground mesh)");
    t.selection.materials = r.strings("vegetation_materials", 1024);
    r.finish();
}

// "terrain": procedural keys, or one of "heightmap" / "mesh" (then the procedural keys do not apply).
void readTerrain(JsonReader r, Scene& scene) {
    TerrainParams& t = scene.terrain;
    const bool heightmap = r.has("heightmap"), mesh = r.has("mesh");
    if (heightmap && mesh) r.fail("'terrain' takes either 'heightmap' or 'mesh', not both");
    if (heightmap || mesh)
        for (const char* key : {"size", "spacing", "amplitude", "feature_size", "octaves"})
            if (r.has(key))
                r.fail(r.name(key) + " applies to the procedural terrain only, not to 'terrain." +
                       (heightmap ? "heightmap'" : "mesh'"));
    if (heightmap) {
        t.source = TerrainParams::Source::Heightmap;
        readHeightmap(r.child("heightmap"), scene, t.heightmap);
    } else if (mesh) {
        t.source = TerrainParams::Source::Mesh;
        readGroundMesh(r.child("mesh"), scene, t);
    } else {
        readProceduralTerrain(r, t.procedural);
    }
    t.selection.maxSlopeDegrees = r.number("max_slope_deg", t.selection.maxSlopeDegrees, 1.0, 90.0);
    // In the order of gpu::kGroundMaterial*.
    t.material = uint32_t(r.choice("material", int(t.material), {"soil", "dry_soil", "mud", "gravel", "forest_floor"}));
    static_assert(gpu::kGroundMaterialForestFloor == 4 && gpu::kGroundMaterialCount == 5);
    r.finish();
}

void readSun(JsonReader r, SunParams& sun) {
    sun.azimuthDegrees = r.number("azimuth_deg", sun.azimuthDegrees, -360.0, 360.0);
    sun.elevationDegrees = r.number("elevation_deg", sun.elevationDegrees, -90.0, 90.0);
    sun.radiance = toVec3(r.vector<3>("radiance", glm::dvec3(sun.radiance), 0.0, 1e6));
    r.finish();
}

void readSky(JsonReader r, SkyParams& sky) {
    const bool colours = r.has("zenith") || r.has("horizon");
    sky.model = SkyParams::Model(r.choice("model", colours ? 1 : 0, {"physical", "gradient"}));
    if (sky.model == SkyParams::Model::Physical && colours)
        r.fail("'" + r.path() +
               "': 'zenith' and 'horizon' belong to the gradient model (the physical sky's "
               "colours come from the sun and 'turbidity')");
    sky.turbidity = r.number("turbidity", sky.turbidity, 1.7, 10.0);
    sky.clouds = r.number("clouds", sky.clouds, 0.0, 1.0);
    sky.visibility = r.number("visibility_m", sky.visibility, 0.0, 1e6);
    sky.zenith = toVec3(r.vector<3>("zenith", glm::dvec3(sky.zenith), 0.0, 1e6));
    sky.horizon = toVec3(r.vector<3>("horizon", glm::dvec3(sky.horizon), 0.0, 1e6));
    sky.groundAmbient = toVec3(r.vector<3>("ground", glm::dvec3(sky.groundAmbient), 0.0, 1e6));
    r.finish();
}

void readMount(JsonReader r, RigParams& rig) {
    rig.mountObject = r.string("object", "");
    rig.mountNode = r.string("node", "");
    if (rig.mountObject.empty() || rig.mountNode.empty())
        r.fail("'" + r.path() + "' needs 'object' and 'node' (names of a scene object and a node of its model)");
    rig.mountOffset = r.vector<3>("offset", rig.mountOffset, -1e3, 1e3);
    rig.mountPitchDegrees = r.number("pitch_deg", rig.mountPitchDegrees, -90.0, 90.0);
    r.finish();
}

// The stereo rig's keys live in the "camera" object next to the camera's own.
void readRig(JsonReader& camera, RigParams& rig) {
    rig.baseline = camera.number("baseline", rig.baseline, 0.0, 100.0);
    rig.minDepth = camera.number("min_depth", rig.minDepth, 0.01, 1e4);
    rig.focalLengthPx = camera.number("focal_length_px", rig.focalLengthPx, 0.0, 1e6);
    rig.hasPrincipalPoint = camera.has("principal_point");
    rig.principalPoint = camera.vector<2>("principal_point", rig.principalPoint, -1e5, 1e5);
    if (camera.has("mount")) readMount(camera.child("mount"), rig);
    if (const nlohmann::json* sensor = camera.raw("sensor"))
        rig.sensor = parseSensor(*sensor, camera.source(), camera.childPath("sensor"));
    if (rig.sensor.stereoOffsetSeconds != 0.0 && !rig.stereo()) // the offset is the right camera's
        camera.fail("'" + camera.childPath("sensor") + ".stereo_offset_s' needs a stereo rig ('" +
                    camera.childPath("baseline") + "' > 0): a single camera has no right view to offset");
}

void readCamera(JsonReader r, CameraParams& c) {
    c.position = r.vector<3>("position", c.position, -1e6, 1e6);
    c.useHeightAboveGround = r.has("height_above_ground") || !r.has("position");
    c.heightAboveGround = r.number("height_above_ground", c.heightAboveGround, -1e4, 1e5);
    c.lookAt = r.vector<3>("look_at", c.lookAt, -1e6, 1e6);
    c.lookAtUsesGround = r.has("look_at_height_above_ground") || !r.has("look_at");
    c.lookAtHeightAboveGround = r.number("look_at_height_above_ground", c.lookAtHeightAboveGround, -1e4, 1e5);
    c.fovYDegrees = r.number("fov_y_deg", c.fovYDegrees, 1.0, 170.0);
    if (const nlohmann::json* path = r.raw("path")) {
        c.hasPath = true;
        c.path = parsePath(*path, r.source(), r.childPath("path"));
        if (!path->contains("height_above_ground")) c.path.heightAboveGround = c.heightAboveGround;
    }
    c.lookAhead = r.number("look_ahead", c.lookAhead, 0.1, 1e4);
    readRig(r, c.rig);
    r.finish();
}

void readSequence(JsonReader r, SequenceParams& sequence) {
    sequence.frames = uint32_t(r.integer("frames", sequence.frames, 1, 1000000));
    sequence.timeStep = r.number("time_step", sequence.timeStep, 1e-4, 10.0);
    r.finish();
}

void readRender(JsonReader r, RenderParams& render) {
    const glm::uvec2 resolution = r.wholeVector<2>("resolution", glm::uvec2(render.width, render.height), 1, 16384);
    render.width = resolution.x;
    render.height = resolution.y;
    render.samples = uint32_t(r.integer("samples", render.samples, 1, 4));
    if (render.samples != 1 && render.samples != 4) r.fail(r.name("samples") + " must be 1 or 4");
    render.shadowMapSize = uint32_t(r.integer("shadow_map_size", render.shadowMapSize, 0, 8192));
    render.shadowDistance = r.numberF("shadow_distance", render.shadowDistance, 1.0, 2000.0);
    render.shadowCascades = uint32_t(r.integer("shadow_cascades", render.shadowCascades, 1, gpu::kMaxShadowCascades));
    render.flow = r.boolean("flow", render.flow);
    r.finish();
    checkRenderResolution(render, r.source());
}

void readLod(JsonReader r, LodParams& l) {
    l.nearToMid = r.numberF("near", l.nearToMid, 0.0, 1e4);
    l.midToFar = r.numberF("mid", l.midToFar, 0.0, 1e4);
    l.farLimit = r.numberF("far", l.farLimit, 0.0, 1e5);
    l.band = r.numberF("band", l.band, 0.01, 100.0);
    l.sliceLayers = r.numberF("slice_layers", l.sliceLayers, 0.0, 100.0);
    l.mergeWidth = r.numberF("merge_width", l.mergeWidth, 0.0, 64.0);
    l.depthMerge = r.numberF("depth_merge", l.depthMerge, 0.0, 64.0);
    l.nearBlades = uint32_t(r.integer("near_blades", l.nearBlades, 0, gpu::kMaxNearBlades));
    if (l.sliceLayers > 0.0f && l.sliceLayers < 2.0f)
        r.fail(r.name("slice_layers") +
               " must be 0 (off) or at least 2 (fewer would show the ground through the plants)");
    if (!(l.nearToMid <= l.midToFar && l.midToFar <= l.farLimit))
        r.fail("'" + r.path() + "' distances must satisfy near <= mid <= far");
    r.finish();
}

void readWind(JsonReader r, WindParams& w) {
    w.directionDegrees = r.number("direction_deg", w.directionDegrees, -360.0, 360.0);
    w.strength = r.numberF("strength", w.strength, 0.0, 0.9);
    w.gustStrength = r.numberF("gust_strength", w.gustStrength, 0.0, 0.9);
    w.gustFrequency = r.numberF("gust_frequency", w.gustFrequency, 0.0, 10.0);
    w.gustWavelength = r.numberF("gust_wavelength", w.gustWavelength, 1.0, 1e4);
    w.flutter = r.numberF("flutter", w.flutter, 0.0, 0.5);
    r.finish();
}

void readAtlas(JsonReader r, Scene& scene) {
    scene.atlasPngPath = assetPath(r, "png", scene);
    scene.atlasJsonPath = assetPath(r, "json", scene);
    if (scene.atlasPngPath.empty() != scene.atlasJsonPath.empty())
        r.fail("'" + r.path() + "' needs both 'png' and 'json'");
    r.finish();
}

// "interaction", "vehicles", "colliders", "gusts" and "objects": everything that moves or bends the plants.
void readActors(JsonReader& root, Scene& scene) {
    if (const nlohmann::json* interaction = root.raw("interaction"))
        scene.interaction = parseInteractionParams(*interaction, scene.source);
    // One clock: the interaction ticks with the sequence's frames.
    scene.interaction.recovery.timeStep = float(scene.sequence.timeStep);
    // Gusts follow the scene seed (and so --seed) unless the scene pins their own.
    scene.actors = parseActors(root, scene.seed);
    checkArrayLength(root, "objects", kMaxSceneObjects, "models to load, instance ids");
    scene.objects = parseObjects(root, sceneFolder(scene.source), scene.assets);
}

// "land_cover": a grass map made from a land-cover raster instead of "grass_map"; its file is an asset like grass_map's.
void readLandCover(JsonReader& root, Scene& scene) {
    if (root.has("grass_map")) root.fail("'grass_map' and 'land_cover' both give the grass map; keep one of them");
    JsonReader r = root.child("land_cover");
    scene.landCover = parseLandCoverParams(r);
    r.required("file", "the raster of land-cover class codes");
    scene.landCover.file = assetPath(r, "file", scene);
    requireComponent(Component::Gdal, r.source() + ": " + r.name("file")); // the raster of class codes
    r.finish();
}

// "vegetation", "vegetation_enabled", "grass_map" and "land_cover". Needs the terrain (the tile covers it by default).
void readVegetation(JsonReader& root, Scene& scene) {
    const std::string& source = scene.source;
    const nlohmann::json* vegetation = root.raw("vegetation");
    if (vegetation) scene.vegetation = parseVegetationParams(*vegetation, source);
    if (!vegetation || !vegetation->contains("seed")) scene.vegetation.seed = scene.seed;
    scene.vegetationTileSet = vegetation && vegetation->contains("tile_size");
    scene.vegetationOriginSet = vegetation && vegetation->contains("world_origin");
    // The vegetation tile covers the terrain unless told otherwise (a loaded ground's extent: vegetationOn).
    const bool procedural = scene.terrain.source == TerrainParams::Source::Procedural;
    if (procedural && !scene.vegetationTileSet) {
        scene.vegetation.tileSize = scene.terrain.procedural.size;
        validateVegetationParams(scene.vegetation, source + " (vegetation.tile_size = terrain.size)");
    }
    if (const nlohmann::json* enabled = root.raw("vegetation_enabled"); enabled && enabled->is_boolean())
        scene.vegetationEnabled = enabled->get<bool>();
    else
        scene.vegetationEnabled = root.number("vegetation_enabled", 1.0, 0.0, 1.0) != 0.0;
    scene.grassMapPath = assetPath(root, "grass_map", scene);
    if (root.has("land_cover")) readLandCover(root, scene);
    if (procedural && scene.vegetation.tileSize > scene.terrain.procedural.size + 1e-3f)
        root.fail("'vegetation.tile_size' (" + std::to_string(scene.vegetation.tileSize) +
                  " m) must not exceed 'terrain.size' (" + std::to_string(scene.terrain.procedural.size) + " m)");
}

} // namespace

glm::vec3 SunParams::direction() const {
    double az = azimuthDegrees * std::numbers::pi / 180.0, el = elevationDegrees * std::numbers::pi / 180.0;
    return glm::vec3(float(std::sin(az) * std::cos(el)), float(std::cos(az) * std::cos(el)), float(std::sin(el)));
}

void updateSceneSection(Scene& scene, const std::string& key, const nlohmann::json& value, const std::string& source) {
    nlohmann::json section = value;
    if (key == "sky" && section.is_object() && !section.contains("model") && !section.contains("zenith") &&
        !section.contains("horizon"))
        section["model"] = scene.sky.model == SkyParams::Model::Gradient ? "gradient" : "physical";
    const nlohmann::json root = {{key, section}};
    JsonReader reader(root, source);
    // Read into copies, so that an error changes nothing.
    WindParams wind = scene.wind;
    SunParams sun = scene.sun;
    SkyParams sky = scene.sky;
    require(key == "wind" || key == "sun" || key == "sky", source + ": no section '" + key + "' (wind, sun or sky)");
    if (key == "wind") readWind(reader.child("wind"), wind);
    if (key == "sun") readSun(reader.child("sun"), sun);
    if (key == "sky") readSky(reader.child("sky"), sky);
    scene.wind = wind, scene.sun = sun, scene.sky = sky;
}

Scene parseScene(const nlohmann::json& json, const std::string& source, const AssetPolicy& assets) {
    Scene scene;
    scene.source = source;
    scene.assets = assets;
    JsonReader root(json, source);
    scene.name = root.string("name", scene.name);
    scene.seed = root.integer("seed", scene.seed, 0, UINT64_MAX);
    readTerrain(root.child("terrain"), scene);
    scene.terrain.procedural.seed = scene.seed;
    readSun(root.child("sun"), scene.sun);
    readSky(root.child("sky"), scene.sky);
    readCamera(root.child("camera"), scene.camera);
    readSequence(root.child("sequence"), scene.sequence);
    readRender(root.child("render"), scene.render);
    readLod(root.child("lod"), scene.lod);
    readWind(root.child("wind"), scene.wind);
    readActors(root, scene);
    readAtlas(root.child("atlas"), scene);
    readVegetation(root, scene);
    if (root.has("world")) scene.world = parseWorldParams(root.child("world"));
    if (demWorld(scene)) fitWorldToDem(scene, root.raw("world")->contains("tiles")); // the DEM's lattice and extent
    scene.rangeSensors = parseRangeSensors(root);
    root.finish();
    checkSceneLimits(scene);
    if (scene.world.enabled) checkWorldScene(scene);
    return scene;
}

Scene loadScene(const std::string& path, std::optional<uint64_t> seed,
                const std::vector<std::string>& allowedAssetDirs) {
    return loadSceneInput(SceneInput{.path = path, .seed = seed, .allowedAssetDirs = allowedAssetDirs});
}

Atlas buildAtlas(const Scene& scene) {
    Atlas atlas = scene.atlasPngPath.empty() ? generateAtlas(AtlasGenParams{.seed = 7})
                                             : loadAtlas(scene.atlasPngPath, scene.atlasJsonPath);
    buildMipChain(atlas);
    return atlas;
}

GrassMap buildGrassMap(const Scene& scene, float tileSize, glm::dvec2 origin) {
    if (!scene.grassMapPath.empty() && scene.world.enabled) return worldGrassMapWindow(scene, origin);
    if (!scene.grassMapPath.empty()) return loadGrassMap(scene.grassMapPath);
    if (!scene.landCover.file.empty() && scene.world.enabled) return worldLandCoverGrassMap(scene, origin);
    if (!scene.landCover.file.empty())
        return loadLandCoverGrassMap(scene.landCover, tileSize, scene.source + ": 'land_cover'", 0,
                                     scene.assets.folders());
    return makeMeadowGrassMap({.tileSize = tileSize, .seed = scene.seed, .origin = origin});
}

VegetationTile buildVegetation(const Scene& scene, const Ground& terrain, const GrassMap& map, uint32_t threads) {
    return generateTile(terrain, map, vegetationOn(scene, terrain), TileCoord{0, 0}, threads);
}

VegetationTile buildVegetation(const Scene& scene, const Ground& terrain, uint32_t threads) {
    return buildVegetation(scene, terrain, buildGrassMap(scene, vegetationOn(scene, terrain).tileSize), threads);
}

Camera sceneCamera(const Scene& scene, const Ground& terrain, uint32_t width, uint32_t height, double time) {
    const CameraParams& c = scene.camera;
    if (c.hasPath) {
        glm::dvec3 position = pathPose(c.path, terrain, time).position;
        glm::dvec3 target = pathPointAhead(c.path, terrain, time, c.lookAhead);
        target.z += c.lookAtHeightAboveGround;
        return Camera::lookAt(position, target, glm::dvec3(0.0, 0.0, 1.0), c.fovYDegrees, width, height);
    }
    glm::dvec3 position = c.position, target = c.lookAt;
    if (c.useHeightAboveGround) position.z = terrain.height(glm::vec2(position)) + c.heightAboveGround;
    if (c.lookAtUsesGround) target.z = terrain.height(glm::vec2(target)) + c.lookAtHeightAboveGround;
    return Camera::lookAt(position, target, glm::dvec3(0.0, 0.0, 1.0), c.fovYDegrees, width, height);
}

std::vector<Collider> sceneColliders(const Scene& scene, const std::vector<ObjectModel>& models, const Ground& terrain,
                                     uint64_t tick) {
    const double time = double(tick) * scene.sequence.timeStep;
    std::vector<Collider> colliders = actorColliders(scene.actors, terrain, time, tick, float(scene.sequence.timeStep));
    if (!models.empty()) {
        std::vector<Collider> objects = objectColliders(scene.objects, models, terrain, time);
        colliders.insert(colliders.end(), objects.begin(), objects.end());
    }
    return colliders;
}

bool sceneHasColliders(const Scene& scene) {
    if (!scene.actors.empty()) return true;
    for (const ObjectParams& object : scene.objects)
        if (!object.colliders.empty()) return true;
    return false;
}

bool sceneMakesRuts(const Scene& scene) {
    for (const VehicleParams& vehicle : scene.actors.vehicles)
        if (vehicle.rut.depth > 0.0f) return true;
    for (const MovingColliderParams& moving : scene.actors.colliders)
        if (moving.collider.rut.depth > 0.0f) return true;
    for (const ObjectParams& object : scene.objects)
        for (const ObjectColliderParams& collider : object.colliders)
            if (collider.rut.depth > 0.0f) return true;
    return false;
}

void parseResolution(const std::string& text, uint32_t& width, uint32_t& height) {
    const std::string what = "bad resolution '" + text + "'";
    const size_t x = text.find_first_of("xX");
    const std::string_view w = std::string_view(text).substr(0, x == std::string::npos ? text.size() : x);
    const std::string_view h = x == std::string::npos ? std::string_view() : std::string_view(text).substr(x + 1);
    require(x != std::string::npos && h.find_first_of("xX") == std::string_view::npos,
            what + ": expected WIDTHxHEIGHT, e.g. 1280x720");
    const uint64_t wide = parseUnsigned(w, 1, kMaxImageSide, what + ": width");
    const uint64_t high = parseUnsigned(h, 1, kMaxImageSide, what + ": height");
    require(wide * high <= kMaxImagePixels, what + ": " + std::to_string(wide * high) + " pixels, more than the " +
                                                std::to_string(kMaxImagePixels) + " (8192x8192) allowed");
    width = uint32_t(wide);
    height = uint32_t(high);
}

} // namespace sward

#include "scene/scene.h"

#include "common/error.h"
#include "world/ground.h"
#include "vegetation/placement.h"

#include <filesystem>

#include <cmath>
#include <fstream>
#include <numbers>
#include <set>

namespace sward {

namespace {

// Reads typed, range-checked values from one JSON object and rejects keys nobody asked for.
class Reader {
public:
    Reader(const nlohmann::json& json, std::string source, std::string path)
        : json_(json), source_(std::move(source)), path_(std::move(path)) {
        if (!json_.is_object()) fail(path_.empty() ? "the scene must be a JSON object" : path_ + " must be an object");
    }

    double number(const char* key, double value, double lo, double hi) {
        if (const nlohmann::json* v = find(key)) {
            if (!v->is_number()) fail(name(key) + " must be a number");
            value = v->get<double>();
            if (!std::isfinite(value) || value < lo || value > hi)
                fail(name(key) + " must be between " + fmt(lo) + " and " + fmt(hi) + " (got " + fmt(value) + ")");
        }
        return value;
    }
    uint64_t integer(const char* key, uint64_t value, uint64_t lo, uint64_t hi) {
        if (const nlohmann::json* v = find(key)) {
            if (!v->is_number_integer() ||
                (v->is_number_integer() && v->get<int64_t>() < 0 && !v->is_number_unsigned()))
                fail(name(key) + " must be a non-negative integer");
            value = v->get<uint64_t>();
            if (value < lo || value > hi)
                fail(name(key) + " must be between " + std::to_string(lo) + " and " + std::to_string(hi) + " (got " +
                     std::to_string(value) + ")");
        }
        return value;
    }
    std::string string(const char* key, std::string value) {
        if (const nlohmann::json* v = find(key)) {
            if (!v->is_string()) fail(name(key) + " must be a string");
            value = v->get<std::string>();
        }
        return value;
    }
    template <int N> glm::vec<N, double> vector(const char* key, glm::vec<N, double> value, double lo, double hi) {
        if (const nlohmann::json* v = find(key)) {
            if (!v->is_array() || v->size() != N)
                fail(name(key) + " must be an array of " + std::to_string(N) + " numbers");
            for (int i = 0; i < N; ++i) {
                const nlohmann::json& e = (*v)[size_t(i)];
                if (!e.is_number() || !std::isfinite(e.get<double>()) || e.get<double>() < lo || e.get<double>() > hi)
                    fail(name(key) + " must hold numbers between " + fmt(lo) + " and " + fmt(hi));
                value[i] = e.get<double>();
            }
        }
        return value;
    }
    bool has(const char* key) const { return json_.contains(key); }
    Reader child(const char* key) {
        seen_.insert(key);
        static const nlohmann::json empty = nlohmann::json::object();
        return Reader(json_.contains(key) ? json_.at(key) : empty, source_, path_.empty() ? key : path_ + "." + key);
    }
    const nlohmann::json* raw(const char* key) { return find(key); }
    // Call after reading: any key not read is a typo or an unsupported option.
    void finish() const {
        for (auto it = json_.begin(); it != json_.end(); ++it)
            if (!seen_.count(it.key())) fail("unknown key " + name(it.key().c_str()));
    }

private:
    const nlohmann::json* find(const char* key) {
        seen_.insert(key);
        auto it = json_.find(key);
        return it == json_.end() ? nullptr : &*it;
    }
    std::string name(const char* key) const {
        std::string full = "'";
        if (!path_.empty()) full.append(path_).append(".");
        return full.append(key).append("'");
    }
    static std::string fmt(double v) {
        char buffer[32];
        std::snprintf(buffer, sizeof buffer, "%g", v);
        return buffer;
    }
    [[noreturn]] void fail(const std::string& message) const { throw Error(source_ + ": " + message); }

    const nlohmann::json& json_;
    std::string source_, path_;
    std::set<std::string> seen_;
};

glm::vec3 toVec3(glm::dvec3 v) {
    return glm::vec3(v);
}

} // namespace

glm::vec3 SunParams::direction() const {
    double az = azimuthDegrees * std::numbers::pi / 180.0, el = elevationDegrees * std::numbers::pi / 180.0;
    return glm::vec3(float(std::sin(az) * std::cos(el)), float(std::cos(az) * std::cos(el)), float(std::sin(el)));
}

Scene parseScene(const nlohmann::json& json, const std::string& source) {
    Scene scene;
    scene.source = source;
    Reader root(json, source, "");
    scene.name = root.string("name", scene.name);
    scene.seed = root.integer("seed", scene.seed, 0, UINT64_MAX);

    Reader terrain = root.child("terrain");
    ProceduralTerrainParams& t = scene.terrain;
    t.size = float(terrain.number("size", t.size, 10.0, 4000.0));
    t.spacing = float(terrain.number("spacing", t.spacing, 0.1, 50.0));
    t.amplitude = float(terrain.number("amplitude", t.amplitude, 0.0, 1000.0));
    t.featureSize = float(terrain.number("feature_size", t.featureSize, 1.0, 10000.0));
    t.octaves = uint32_t(terrain.integer("octaves", t.octaves, 1, 8));
    if (t.size / t.spacing > 8192.0f) throw Error(source + ": 'terrain.size' / 'terrain.spacing' exceeds 8192 cells");
    terrain.finish();
    t.seed = scene.seed;

    Reader sun = root.child("sun");
    scene.sun.azimuthDegrees = sun.number("azimuth_deg", scene.sun.azimuthDegrees, -360.0, 360.0);
    scene.sun.elevationDegrees = sun.number("elevation_deg", scene.sun.elevationDegrees, -90.0, 90.0);
    scene.sun.radiance = toVec3(sun.vector<3>("radiance", glm::dvec3(scene.sun.radiance), 0.0, 1e6));
    sun.finish();

    Reader sky = root.child("sky");
    scene.sky.zenith = toVec3(sky.vector<3>("zenith", glm::dvec3(scene.sky.zenith), 0.0, 1e6));
    scene.sky.horizon = toVec3(sky.vector<3>("horizon", glm::dvec3(scene.sky.horizon), 0.0, 1e6));
    scene.sky.groundAmbient = toVec3(sky.vector<3>("ground", glm::dvec3(scene.sky.groundAmbient), 0.0, 1e6));
    sky.finish();

    Reader camera = root.child("camera");
    CameraParams& c = scene.camera;
    c.position = camera.vector<3>("position", c.position, -1e6, 1e6);
    c.useHeightAboveGround = camera.has("height_above_ground") || !camera.has("position");
    c.heightAboveGround = camera.number("height_above_ground", c.heightAboveGround, -1e4, 1e5);
    c.lookAt = camera.vector<3>("look_at", c.lookAt, -1e6, 1e6);
    c.lookAtUsesGround = camera.has("look_at_height_above_ground") || !camera.has("look_at");
    c.lookAtHeightAboveGround = camera.number("look_at_height_above_ground", c.lookAtHeightAboveGround, -1e4, 1e5);
    c.fovYDegrees = camera.number("fov_y_deg", c.fovYDegrees, 1.0, 170.0);
    if (const nlohmann::json* path = camera.raw("path")) {
        c.hasPath = true;
        c.path = parsePath(*path, source + ": 'camera.path'");
        if (!path->contains("height_above_ground")) c.path.heightAboveGround = c.heightAboveGround;
    }
    c.lookAhead = camera.number("look_ahead", c.lookAhead, 0.1, 1e4);
    RigParams& rig = c.rig;
    rig.baseline = camera.number("baseline", rig.baseline, 0.0, 100.0);
    rig.minDepth = camera.number("min_depth", rig.minDepth, 0.01, 1e4);
    rig.focalLengthPx = camera.number("focal_length_px", rig.focalLengthPx, 0.0, 1e6);
    rig.hasPrincipalPoint = camera.has("principal_point");
    rig.principalPoint = camera.vector<2>("principal_point", rig.principalPoint, -1e5, 1e5);
    if (camera.has("mount")) {
        Reader mount = camera.child("mount");
        rig.mountObject = mount.string("object", "");
        rig.mountNode = mount.string("node", "");
        if (rig.mountObject.empty() || rig.mountNode.empty())
            throw Error(source + ": 'camera.mount' needs 'object' and 'node' (names of a scene object and a node of its model)");
        rig.mountOffset = mount.vector<3>("offset", rig.mountOffset, -1e3, 1e3);
        rig.mountPitchDegrees = mount.number("pitch_deg", rig.mountPitchDegrees, -90.0, 90.0);
        mount.finish();
    }
    if (const nlohmann::json* sensor = camera.raw("sensor")) rig.sensor = parseSensor(*sensor, "camera.sensor", source);
    camera.finish();

    Reader sequence = root.child("sequence");
    scene.sequence.frames = uint32_t(sequence.integer("frames", scene.sequence.frames, 1, 1000000));
    scene.sequence.timeStep = sequence.number("time_step", scene.sequence.timeStep, 1e-4, 10.0);
    sequence.finish();

    Reader render = root.child("render");
    glm::dvec2 resolution =
        render.vector<2>("resolution", glm::dvec2(scene.render.width, scene.render.height), 1, 16384);
    if (resolution.x != std::floor(resolution.x) || resolution.y != std::floor(resolution.y))
        throw Error(source + ": 'render.resolution' must hold whole numbers");
    scene.render.width = uint32_t(resolution.x);
    scene.render.height = uint32_t(resolution.y);
    scene.render.samples = uint32_t(render.integer("samples", scene.render.samples, 1, 4));
    if (scene.render.samples != 1 && scene.render.samples != 4)
        throw Error(source + ": 'render.samples' must be 1 or 4");
    scene.render.shadowMapSize = uint32_t(render.integer("shadow_map_size", scene.render.shadowMapSize, 0, 8192));
    scene.render.shadowDistance = float(render.number("shadow_distance", scene.render.shadowDistance, 1.0, 2000.0));
    render.finish();

    Reader lod = root.child("lod");
    LodParams& l = scene.lod;
    l.nearToMid = float(lod.number("near", l.nearToMid, 0.0, 1e4));
    l.midToFar = float(lod.number("mid", l.midToFar, 0.0, 1e4));
    l.farLimit = float(lod.number("far", l.farLimit, 0.0, 1e5));
    l.band = float(lod.number("band", l.band, 0.01, 100.0));
    if (!(l.nearToMid <= l.midToFar && l.midToFar <= l.farLimit))
        throw Error(source + ": 'lod' distances must satisfy near <= mid <= far");
    lod.finish();

    Reader wind = root.child("wind");
    WindParams& w = scene.wind;
    w.directionDegrees = wind.number("direction_deg", w.directionDegrees, -360.0, 360.0);
    w.strength = float(wind.number("strength", w.strength, 0.0, 0.9));
    w.gustStrength = float(wind.number("gust_strength", w.gustStrength, 0.0, 0.9));
    w.gustFrequency = float(wind.number("gust_frequency", w.gustFrequency, 0.0, 10.0));
    w.gustWavelength = float(wind.number("gust_wavelength", w.gustWavelength, 1.0, 1e4));
    w.flutter = float(wind.number("flutter", w.flutter, 0.0, 0.5));
    wind.finish();

    if (const nlohmann::json* interaction = root.raw("interaction"))
        scene.interaction = parseInteractionParams(*interaction, source);
    // One clock: the interaction ticks with the sequence's frames.
    scene.interaction.recovery.timeStep = float(scene.sequence.timeStep);
    scene.actors = parseActors(root.raw("vehicles"), root.raw("colliders"), root.raw("gusts"), source);
    // Gusts follow the scene seed (and so --seed) unless the scene pins their own.
    if (const nlohmann::json* gusts = root.raw("gusts"); !gusts || !gusts->is_object() || !gusts->contains("seed"))
        scene.actors.gusts.seed = scene.seed;
    // Model paths are relative to the scene file's folder (built-in scenes, "<...>", use them as given).
    scene.objects = parseObjects(root.raw("objects"), source,
                                 source.find('<') == std::string::npos ? std::filesystem::path(source).parent_path().string()
                                                                      : std::string());

    Reader atlas = root.child("atlas");
    auto resolve = [&](std::string path) {
        if (!path.empty() && std::filesystem::path(path).is_relative() && source.find('<') == std::string::npos)
            path = (std::filesystem::path(source).parent_path() / path).string();
        return path;
    };
    scene.atlasPngPath = resolve(atlas.string("png", ""));
    scene.atlasJsonPath = resolve(atlas.string("json", ""));
    if (scene.atlasPngPath.empty() != scene.atlasJsonPath.empty())
        throw Error(source + ": 'atlas' needs both 'png' and 'json'");
    atlas.finish();

    const nlohmann::json* vegetation = root.raw("vegetation");
    if (vegetation) scene.vegetation = parseVegetationParams(*vegetation, source);
    if (!vegetation || !vegetation->contains("seed")) scene.vegetation.seed = scene.seed;
    // The vegetation tile covers the terrain unless told otherwise.
    if (!vegetation || !vegetation->contains("tile_size")) {
        scene.vegetation.tileSize = scene.terrain.size;
        validateVegetationParams(scene.vegetation, source + " (vegetation.tile_size = terrain.size)");
    }
    if (const nlohmann::json* enabled = root.raw("vegetation_enabled"); enabled && enabled->is_boolean())
        scene.vegetationEnabled = enabled->get<bool>();
    else
        scene.vegetationEnabled = root.number("vegetation_enabled", 1.0, 0.0, 1.0) != 0.0;
    scene.grassMapPath = resolve(root.string("grass_map", ""));
    if (scene.vegetation.tileSize > scene.terrain.size + 1e-3f)
        throw Error(source + ": 'vegetation.tile_size' (" + std::to_string(scene.vegetation.tileSize) +
                    " m) must not exceed 'terrain.size' (" + std::to_string(scene.terrain.size) + " m)");
    root.finish();
    return scene;
}

Scene loadScene(const std::string& path, std::optional<uint64_t> seed) {
    nlohmann::json json = nlohmann::json::object();
    if (!path.empty()) {
        std::ifstream file(path);
        if (!file) throw Error("cannot open scene file '" + path + "'");
        try {
            json = nlohmann::json::parse(file);
        } catch (const nlohmann::json::parse_error& e) {
            throw Error("scene file '" + path + "' is not valid JSON: " + e.what());
        }
    }
    if (seed && json.is_object()) json["seed"] = *seed; // before parsing: every seed derived from it follows
    return parseScene(json, path.empty() ? "<built-in>" : path);
}

Heightfield buildTerrain(const Scene& scene) {
    return makeProceduralTerrain(scene.terrain);
}

Atlas buildAtlas(const Scene& scene) {
    Atlas atlas = scene.atlasPngPath.empty() ? generateAtlas(AtlasGenParams{.seed = 7})
                                             : loadAtlas(scene.atlasPngPath, scene.atlasJsonPath);
    buildMipChain(atlas);
    return atlas;
}

GrassMap buildGrassMap(const Scene& scene) {
    if (!scene.grassMapPath.empty()) return loadGrassMap(scene.grassMapPath);
    return makeMeadowGrassMap({.tileSize = scene.vegetation.tileSize, .seed = scene.seed});
}

VegetationTile buildVegetation(const Scene& scene, const Heightfield& terrain, uint32_t threads) {
    return generateTile(Ground(terrain), buildGrassMap(scene), scene.vegetation, TileCoord{0, 0}, threads);
}

Camera sceneCamera(const Scene& scene, const Heightfield& terrain, uint32_t width, uint32_t height, double time) {
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

std::vector<Collider> sceneColliders(const Scene& scene, const std::vector<ObjectModel>& models,
                                     const Heightfield& terrain, uint64_t tick) {
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

void parseResolution(const std::string& text, uint32_t& width, uint32_t& height) {
    unsigned w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%u%c%u%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w < 1 || h < 1 ||
        w > 16384 || h > 16384 || text.find_first_not_of("0123456789xX") != std::string::npos)
        throw Error("bad resolution '" + text +
                    "': expected WIDTHxHEIGHT with each between 1 and 16384, e.g. 1280x720");
    width = w;
    height = h;
}

} // namespace sward

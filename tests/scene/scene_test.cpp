#include "common/error.h"
#include "engine/memory.h"
#include "scene/rover_model.h"
#include "scene/scene.h"
#include "shared/gpu_layout.h"
#include "world/camera.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace sward;

namespace {
std::string errorOf(const char* json) {
    try {
        parseScene(nlohmann::json::parse(json), "s.json");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}
} // namespace

TEST(Scene, DefaultsAreValid) {
    Scene scene = parseScene(nlohmann::json::object(), "empty");
    EXPECT_EQ(scene.render.samples, 4u);
    EXPECT_GT(scene.terrain.procedural.size, 0.0f);
}

TEST(Scene, RejectsBadValuesNamingFileAndKey) {
    EXPECT_NE(errorOf(R"({"terrain": {"amplitude": -1}})").find("s.json: 'terrain.amplitude'"), std::string::npos);
    EXPECT_NE(errorOf(R"({"terrain": {"spacing": "2"}})").find("'terrain.spacing' must be a number"),
              std::string::npos);
    EXPECT_NE(errorOf(R"({"terain": {}})").find("unknown key 'terain'"), std::string::npos);
    EXPECT_NE(errorOf(R"({"render": {"samples": 2}})").find("render.samples"), std::string::npos);
    EXPECT_NE(errorOf(R"({"camera": {"position": [1, 2]}})").find("camera.position"), std::string::npos);
    EXPECT_NE(errorOf(R"([1, 2])").find("JSON object"), std::string::npos);
    EXPECT_NE(errorOf(R"({"lod": {"slice_layers": 1}})").find("'lod.slice_layers' must be 0 (off) or at least 2"),
              std::string::npos);
    EXPECT_EQ(parseScene(nlohmann::json::parse(R"({"lod": {"slice_layers": 0}})"), "s.json").lod.sliceLayers, 0.0f);
}

TEST(Scene, TerrainMaterialNamesAPresetOfAnyGround) {
    EXPECT_EQ(parseScene(nlohmann::json::object(), "s.json").terrain.material, gpu::kGroundMaterialSoil);
    EXPECT_EQ(parseScene(nlohmann::json::parse(R"({"terrain": {"material": "gravel"}})"), "s.json").terrain.material,
              gpu::kGroundMaterialGravel);
    EXPECT_EQ(
        parseScene(nlohmann::json::parse(R"({"terrain": {"material": "forest_floor"}})"), "s.json").terrain.material,
        gpu::kGroundMaterialForestFloor);
    EXPECT_NE(errorOf(R"({"terrain": {"material": "sand"}})")
                  .find("'terrain.material' must be soil, dry_soil, mud, gravel or forest_floor"),
              std::string::npos);
}

TEST(Scene, ACategoryGroundMaterialNamesAPresetOrDefaultsToTheTerrains) {
    const Scene scene = parseScene(
        nlohmann::json::parse(R"({"vegetation": {"categories": [{"ground_material": "mud"}, {}, {"ground_material":
                                  "forest_floor"}]}})"),
        "s.json");
    EXPECT_EQ(scene.vegetation.categories[0].groundMaterial, int32_t(gpu::kGroundMaterialMud));
    EXPECT_EQ(scene.vegetation.categories[1].groundMaterial, kNoGroundMaterial) << "none: the terrain's";
    EXPECT_EQ(scene.vegetation.categories[2].groundMaterial, int32_t(gpu::kGroundMaterialForestFloor));
    EXPECT_EQ(parseScene(nlohmann::json::object(), "s.json").vegetation.categories[0].groundMaterial,
              kNoGroundMaterial);
    EXPECT_NE(
        errorOf(R"({"vegetation": {"categories": [{"ground_material": "sand"}]}})")
            .find("'vegetation.categories[0].ground_material' must be soil, dry_soil, mud, gravel or forest_floor"),
        std::string::npos);
}

TEST(Scene, MissingFileNamesIt) {
    try {
        loadScene("/nonexistent/scene.json");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.json"), std::string::npos);
    }
}

TEST(Scene, ParsesResolution) {
    uint32_t w = 0, h = 0;
    parseResolution("640x480", w, h);
    EXPECT_EQ(w, 640u);
    EXPECT_EQ(h, 480u);
    for (const char* bad : {"", "640", "640x", "x480", "0x1", "640x480x2", "-1x5", "17000x10", "64 0x480"})
        EXPECT_THROW(parseResolution(bad, w, h), Error) << bad;
}

TEST(Scene, ResolutionRefusesWhatWouldWrapAndCapsThePixelCount) {
    uint32_t w = 7, h = 9;
    for (const char* bad : {"4294967616x240", "320x4294967536", "+320x240", "320x+240", "0x10x240", "16384x16384"})
        EXPECT_THROW(parseResolution(bad, w, h), Error) << bad;
    EXPECT_EQ(w, 7u) << "nothing assigned on error";
    parseResolution("16384x4096", w, h);
    EXPECT_EQ(w, 16384u);
    EXPECT_EQ(h, 4096u);
    parseResolution("8X6", w, h);
    EXPECT_EQ(w, 8u);
}

TEST(Scene, GustsFollowTheSceneSeedUnlessPinned) {
    Scene scene = parseScene(nlohmann::json::parse(R"({"seed": 123456789, "gusts": {"count": 3}})"), "s.json");
    EXPECT_EQ(scene.actors.gusts.seed, 123456789u) << "exact, not rounded through a float";
    EXPECT_EQ(scene.actors.gusts.count, 3u);
    scene = parseScene(nlohmann::json::parse(R"({"seed": 5, "gusts": {"count": 3, "seed": 9}})"), "s.json");
    EXPECT_EQ(scene.actors.gusts.seed, 9u);
    EXPECT_THROW(parseScene(nlohmann::json::parse(R"({"gusts": {"count": 2.5}})"), "s.json"), Error);
}

TEST(Scene, VegetationEnabledTakesBooleansAndColliderShapesMustBeStrings) {
    EXPECT_FALSE(parseScene(nlohmann::json::parse(R"({"vegetation_enabled": false})"), "s.json").vegetationEnabled);
    EXPECT_TRUE(parseScene(nlohmann::json::parse(R"({"vegetation_enabled": 1})"), "s.json").vegetationEnabled);
    try {
        parseScene(nlohmann::json::parse(R"({"colliders": [{"shape": 3, "path": {"points": [[0, 0]]}}]})"), "s.json");
        FAIL() << "a numeric shape must be rejected";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("colliders[0]"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("shape"), std::string::npos) << e.what();
    }
}

TEST(Scene, StereoRigKeysAreReadAndChecked) {
    Scene scene = parseScene(
        nlohmann::json::parse(
            R"({"camera": {"baseline": 0.3, "min_depth": 2, "focal_length_px": 500, "principal_point": [300, 200]}})"),
        "s.json");
    EXPECT_DOUBLE_EQ(scene.camera.rig.baseline, 0.3);
    EXPECT_DOUBLE_EQ(scene.camera.rig.minDepth, 2.0);
    Ground terrain = buildTerrain(scene);
    RigCameras rig = sceneRig(scene, terrain, {}, 640, 480, 0.0);
    EXPECT_DOUBLE_EQ(rig.left.fx, 500.0);
    EXPECT_DOUBLE_EQ(rig.left.cx, 300.0);
    EXPECT_NEAR(glm::length(rig.right.position - rig.left.position), 0.3, 1e-9);
    // The right camera sits along the left camera's +x axis: a point projects d = f B / Z further left.
    glm::dvec3 point = rig.left.position + rig.left.worldFromCamera * glm::dvec3(0.2, 0.1, 7.0);
    glm::dvec3 l = rig.left.project(point), r = rig.right.project(point);
    EXPECT_NEAR(l.x - r.x, 500.0 * 0.3 / 7.0, 1e-9);
    EXPECT_NEAR(l.y, r.y, 1e-9);
    EXPECT_THROW(parseScene(nlohmann::json::parse(R"({"camera": {"mount": {"object": "x"}}})"), "s.json"), Error);
}

// Confinement: <tmp>/scene/s.json may read <tmp>/outside only with --allow-assets <tmp>/outside.
namespace {

namespace fs = std::filesystem;

struct AssetFolders {
    fs::path root = fs::canonical(test::tempDir());
    fs::path scene = root / "scene", outside = root / "outside";
    AssetFolders() {
        fs::create_directories(scene);
        fs::create_directories(outside);
        saveRoverGltf((outside / "m.gltf").string());
        for (const char* file : {"map.png", "atlas.png", "atlas.json"}) std::ofstream(outside / file) << "x";
        std::ofstream(scene / "atlas.json") << "x";
    }
    // The three ways out of the folder for `file` of outside/: `..`, an absolute path, a symlink in the folder.
    std::vector<std::string> waysOut(const std::string& file) const {
        fs::remove(scene / ("link-" + file)); // (asked for again by another key naming the same file)
        fs::create_symlink(outside / file, scene / ("link-" + file));
        return {"../outside/" + file, (outside / file).string(), "link-" + file};
    }
    std::string write(const nlohmann::json& json) const {
        std::ofstream(scene / "s.json") << json.dump();
        return (scene / "s.json").string();
    }
};

// A scene naming `path` under `key`: "model" (objects[0].model), "grass_map", "land_cover" (land_cover.file) or
// "atlas" (atlas.png).
nlohmann::json sceneNaming(const std::string& key, const std::string& path) {
    if (key == "model") return {{"objects", {{{"model", path}, {"path", {{"points", {{10, 10}}}}}}}}};
    if (key == "atlas") return {{"atlas", {{"png", path}, {"json", "atlas.json"}}}};
    if (key == "land_cover") return {{"land_cover", {{"file", path}, {"preset", "esa_worldcover"}}}};
    return {{key, path}};
}

} // namespace

TEST(SceneAssets, PathsLeavingTheSceneFolderAreRefusedWithoutAllowAssets) {
    AssetFolders f;
    const std::vector<std::pair<std::string, std::string>> keys = {{"model", "'objects[0].model'"},
                                                                   {"grass_map", "'grass_map'"},
                                                                   {"land_cover", "'land_cover.file'"},
                                                                   {"atlas", "'atlas.png'"}};
    for (const auto& [key, name] : keys) {
        const std::string file = key == "model" ? "m.gltf" : key == "atlas" ? "atlas.png" : "map.png";
        for (const std::string& path : f.waysOut(file)) {
            const std::string scene = f.write(sceneNaming(key, path));
            test::expectError([&] { loadScene(scene); },
                              {scene + ": " + name + ": '" + path + "' resolves to " + (f.outside / file).string() +
                               ", outside the scene's folder " + f.scene.string() +
                               " (allow with --allow-assets DIR)"});
        }
    }
}

TEST(SceneAssets, AllowAssetsAcceptsTheSameFiles) {
    SWARD_SKIP_WITHOUT(Gdal); // a land-cover raster
    AssetFolders f;
    const std::vector<std::string> allow = {f.outside.string()};
    for (const std::string& path : f.waysOut("m.gltf")) {
        const Scene scene = loadScene(f.write(sceneNaming("model", path)), {}, allow);
        EXPECT_EQ(scene.objects.at(0).model, (f.outside / "m.gltf").string());
        EXPECT_GT(loadObjectModels(scene.objects, scene.source).at(0).triangleCount(), 0u);
    }
    for (const std::string& path : f.waysOut("map.png")) {
        EXPECT_EQ(loadScene(f.write(sceneNaming("grass_map", path)), {}, allow).grassMapPath,
                  (f.outside / "map.png").string());
        EXPECT_EQ(loadScene(f.write(sceneNaming("land_cover", path)), {}, allow).landCover.file,
                  (f.outside / "map.png").string());
    }
    for (const std::string& path : f.waysOut("atlas.png"))
        EXPECT_EQ(loadScene(f.write(sceneNaming("atlas", path)), {}, allow).atlasPngPath,
                  (f.outside / "atlas.png").string());
}

TEST(SceneAssets, AModelsBufferFilesAreConfinedToo) {
    AssetFolders f;
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 0, 1};
    std::ofstream(f.outside / "t.bin", std::ios::binary).write(reinterpret_cast<const char*>(positions), 36);
    std::ofstream(f.scene / "m.gltf") << R"({"asset": {"version": "2.0"}, "meshes": [{"primitives":
        [{"attributes": {"POSITION": 0}}]}], "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3,
        "type": "VEC3"}], "bufferViews": [{"buffer": 0, "byteLength": 36}], "buffers": [{"byteLength": 36,
        "uri": "../outside/t.bin"}]})";
    const std::string path = f.write(sceneNaming("model", "m.gltf"));
    const Scene confined = loadScene(path);
    test::expectError([&] { loadObjectModels(confined.objects, confined.source); },
                      {path + ": 'objects[0].model': glTF model '" + (f.scene / "m.gltf").string() +
                       "': buffer uri: '../outside/t.bin' resolves to " + (f.outside / "t.bin").string()});
    const Scene allowed = loadScene(path, {}, {f.outside.string()});
    EXPECT_EQ(loadObjectModels(allowed.objects, allowed.source).at(0).triangleCount(), 1u);
}

TEST(SceneAssets, BuiltInScenesAndParsedJsonStayUnconfined) {
    EXPECT_FALSE(loadScene("").assets.confined());
    const Scene scene = parseScene(sceneNaming("grass_map", "/etc/passwd"), "s.json");
    EXPECT_EQ(scene.grassMapPath, "/etc/passwd");
}

// "sky": the physical model unless the scene gives gradient colours; the two cannot be mixed.
TEST(Scene, SkyIsPhysicalByDefaultAndAGradientWhereColoursAreGiven) {
    const Scene plain = parseScene(nlohmann::json::object(), "empty");
    EXPECT_EQ(plain.sky.model, SkyParams::Model::Physical);
    EXPECT_EQ(plain.sky.turbidity, 3.0);
    EXPECT_EQ(plain.sky.visibility, 20000.0);
    const Scene gradient = parseScene(nlohmann::json::parse(R"({"sky": {"zenith": [0.2, 0.4, 0.9]}})"), "s.json");
    EXPECT_EQ(gradient.sky.model, SkyParams::Model::Gradient);
    const Scene hazy = parseScene(
        nlohmann::json::parse(R"({"sky": {"turbidity": 6, "clouds": 0.3, "visibility_m": 5000}})"), "s.json");
    EXPECT_EQ(hazy.sky.turbidity, 6.0);
    EXPECT_EQ(hazy.sky.clouds, 0.3);
    EXPECT_EQ(hazy.sky.visibility, 5000.0);
    const std::string mixed = errorOf(R"({"sky": {"model": "physical", "horizon": [1, 1, 1]}})");
    EXPECT_NE(mixed.find("belong to the gradient model"), std::string::npos) << mixed;
    EXPECT_NE(errorOf(R"({"sky": {"model": "hosek"}})").find("sky.model"), std::string::npos);
    EXPECT_NE(errorOf(R"({"sky": {"turbidity": 1}})").find("sky.turbidity"), std::string::npos);
}

// A program's change of wind, sun or sky between frames (updateSceneSection, the Python module's set_wind etc.).
TEST(SceneSection, KeysNotGivenKeepTheirValuesAndAnErrorChangesNothing) {
    Scene scene = parseScene(nlohmann::json::parse(R"({"wind": {"strength": 0.2, "flutter": 0.05},
                                                       "sky": {"zenith": [0.2, 0.3, 0.9]}})"),
                             "scene.json");
    updateSceneSection(scene, "wind", {{"direction_deg", 90}}, "set_wind");
    EXPECT_EQ(scene.wind.directionDegrees, 90.0);
    EXPECT_FLOAT_EQ(scene.wind.strength, 0.2f);
    EXPECT_FLOAT_EQ(scene.wind.flutter, 0.05f);
    EXPECT_EQ(test::errorOf([&] {
                  updateSceneSection(scene, "wind", {{"strength", 0.1}, {"flutter", 2}}, "set_wind");
              }),
              "set_wind: 'wind.flutter' must be between 0 and 0.5 (got 2)");
    EXPECT_FLOAT_EQ(scene.wind.strength, 0.2f); // the valid key of the refused change was not applied either
    updateSceneSection(scene, "sky", {{"ground", {0.1, 0.1, 0.1}}}, "set_sky");
    EXPECT_EQ(scene.sky.model, SkyParams::Model::Gradient); // kept: no model and no colours given
    updateSceneSection(scene, "sun", {{"elevation_deg", 12}}, "set_sun");
    EXPECT_EQ(scene.sun.elevationDegrees, 12.0);
    EXPECT_EQ(test::errorOf([&] { updateSceneSection(scene, "lod", nlohmann::json::object(), "set_lod"); }),
              "set_lod: no section 'lod' (wind, sun or sky)");
}

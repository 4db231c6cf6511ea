// Scene objects (vegetation/objects.h) and the default rover (vegetation/rover_model.h): parsing with JSON-path
// errors, the glTF node hierarchy in sward's Z-up frame, poses on the terrain, colliders riding on nodes.
#include "world/heightfield.h"
#include "common/json_reader.h"
#include "scene/objects.h"
#include "scene/rover_model.h"
#include "scene/scene.h"
#include "test_files.h"

#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>

using namespace sward;
using sward::test::expectError;
using sward::test::tempDir;

namespace {

// A plane z = c + gx * x + gy * y sampled on a grid: the rendered triangulation is exactly that plane.
Ground planeTerrain(float gx, float gy, float c = 5.0f) {
    const uint32_t n = 51;
    std::vector<float> heights;
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i) heights.push_back(c + gx * float(i) * 2.0f + gy * float(j) * 2.0f);
    return Ground(Heightfield(n, n, 2.0f, glm::vec2(0.0f), std::move(heights)));
}

std::string writeRover() {
    const std::string path = (tempDir() / "rover.gltf").string();
    saveRoverGltf(path);
    return path;
}

// The scene's "objects" key holding `objects`, parsed as parseScene does.
std::vector<ObjectParams> parseObjectList(const nlohmann::json& objects, const std::string& source,
                                          const std::string& sceneDir) {
    const nlohmann::json scene = {{"objects", objects}};
    JsonReader reader(scene, source);
    return parseObjects(reader, sceneDir);
}

ObjectParams roverObject(const std::string& model, nlohmann::json path) {
    const nlohmann::json json = nlohmann::json::array({{{"model", model}, {"path", path}}});
    return parseObjectList(json, "t", "").at(0);
}

glm::dvec3 origin(const glm::dmat4& m) {
    return glm::dvec3(m[3]);
}

nlohmann::json parse(const char* text) {
    return nlohmann::json::parse(text);
}

} // namespace

TEST(Rover, GeneratorIsDeterministicAndMatchesTheCommittedAsset) {
    const std::string a = roverGltf(), b = roverGltf();
    EXPECT_EQ(a, b);
    const auto dir = tempDir();
    const std::string path = (dir / "rover.gltf").string(), again = (dir / "again.gltf").string();
    saveRoverGltf(path);
    saveRoverGltf(again);
    std::ifstream fa(path, std::ios::binary), fb(again, std::ios::binary);
    std::stringstream sa, sb;
    sa << fa.rdbuf();
    sb << fb.rdbuf();
    EXPECT_EQ(sa.str(), sb.str());
    EXPECT_EQ(sa.str(), a);
    // The shipped asset is exactly the generator's output: regenerate with
    // `sward-rover --out examples/assets/rover.gltf` after changing the generator.
    std::ifstream committed(std::string(SWARD_SOURCE_DIR) + "/examples/assets/rover.gltf", std::ios::binary);
    ASSERT_TRUE(committed.good()) << "examples/assets/rover.gltf is missing";
    std::stringstream sc;
    sc << committed.rdbuf();
    EXPECT_TRUE(sc.str() == a) << "examples/assets/rover.gltf differs from sward-rover's output";
}

TEST(Rover, ModelHasNamedNodesSizeAndFewTriangles) {
    const ObjectModel model = loadGltfModel(writeRover());
    for (const char* name :
         {"rover", "chassis", "mast", "camera_mount", "wheel_fl", "wheel_fr", "wheel_rl", "wheel_rr"})
        EXPECT_GE(model.findNode(name), 0) << name;
    EXPECT_GE(model.triangleCount(), 300u);
    EXPECT_LE(model.triangleCount(), 2000u);
    // Z-up model frame: x left, y back (front is -y), z up; origin on the ground.
    const glm::vec3 size = model.boundsMax - model.boundsMin;
    EXPECT_NEAR(size.y, 1.0f, 0.02f); // length
    EXPECT_NEAR(size.x, 0.7f, 0.02f); // width
    EXPECT_NEAR(size.z, 0.5f, 0.02f); // height
    EXPECT_NEAR(model.boundsMin.z, 0.0f, 1e-5f);
    // Wheel front-left: left (+x) and in front (-y) of the chassis, hub at the wheel radius.
    const glm::dvec3 fl = origin(model.nodes[size_t(model.findNode("wheel_fl"))].modelFromNode);
    const glm::dvec3 chassis = origin(model.nodes[size_t(model.findNode("chassis"))].modelFromNode);
    EXPECT_NEAR(fl.x, 0.29, 1e-6);
    EXPECT_NEAR(fl.y, -0.35, 1e-6);
    EXPECT_NEAR(fl.z, 0.15, 1e-6);
    EXPECT_GT(fl.x, chassis.x);
    EXPECT_LT(fl.y, chassis.y);
    // The camera head is on top, ahead of the centre.
    const glm::dvec3 camera = origin(model.nodes[size_t(model.findNode("camera_mount"))].modelFromNode);
    EXPECT_NEAR(camera.z, 0.475, 1e-6);
    EXPECT_NEAR(camera.y, -0.30, 1e-6);
    // Every primitive has its material's colour and unit normals that face away from the part's centre.
    size_t coloured = 0;
    for (const ModelNode& node : model.nodes)
        for (const ModelPrimitive& prim : node.primitives) {
            coloured += prim.baseColor != glm::vec4(1.0f);
            ASSERT_EQ(prim.normals.size(), prim.positions.size());
            for (const glm::vec3& n : prim.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
        }
    EXPECT_GT(coloured, 8u);
    const ModelPrimitive& body = model.nodes[size_t(model.findNode("chassis"))].primitives.at(0);
    for (size_t t = 0; t < body.indices.size(); t += 3) {
        glm::vec3 a = body.positions[body.indices[t]], b = body.positions[body.indices[t + 1]],
                  c = body.positions[body.indices[t + 2]];
        glm::vec3 centroid = (a + b + c) / 3.0f;
        EXPECT_GT(glm::dot(glm::cross(b - a, c - a), centroid), 0.0f) << "body triangle " << t / 3 << " faces inward";
    }
}

TEST(Objects, NodeTransformsFollowTheHeadingOnFlatGround) {
    const Ground flat = planeTerrain(0.0f, 0.0f, 2.0f);
    const std::string model = writeRover();
    const ObjectModel rover = loadGltfModel(model);
    // Driving east (+x): left is north (+y).
    ObjectParams east = roverObject(model, {{"points", {{20, 30}, {60, 30}}}, {"speed", 2}});
    glm::dvec3 fl = origin(objectNodeToWorld(east, rover, "wheel_fl", flat, 0.0));
    EXPECT_NEAR(fl.x, 20.35, 1e-6);
    EXPECT_NEAR(fl.y, 30.29, 1e-6);
    EXPECT_NEAR(fl.z, 2.15, 1e-6);
    glm::dvec3 rr = origin(objectNodeToWorld(east, rover, "wheel_rr", flat, 0.0));
    EXPECT_NEAR(rr.x, 19.65, 1e-6);
    EXPECT_NEAR(rr.y, 29.71, 1e-6);
    // Driving north (+y): left is west (-x). Five seconds at 2 m/s.
    ObjectParams north = roverObject(model, {{"points", {{40, 10}, {40, 60}}}, {"speed", 2}});
    fl = origin(objectNodeToWorld(north, rover, "wheel_fl", flat, 5.0));
    EXPECT_NEAR(fl.x, 39.71, 1e-6);
    EXPECT_NEAR(fl.y, 20.35, 1e-6);
    // The camera looks along the heading: the mount's -y axis is the direction of travel.
    const glm::dmat4 mount = objectNodeToWorld(north, rover, "camera_mount", flat, 5.0);
    EXPECT_NEAR(glm::length(-glm::dvec3(mount[1]) - glm::dvec3(0, 1, 0)), 0.0, 1e-9);
    // yaw_deg turns the model: 90 degrees makes it drive sideways (its front towards the path's left).
    ObjectParams turned = east;
    turned.yawDegrees = 90.0;
    fl = origin(objectNodeToWorld(turned, rover, "wheel_fl", flat, 0.0));
    EXPECT_NEAR(fl.x, 20.0 - 0.29, 1e-6);
    EXPECT_NEAR(fl.y, 30.0 + 0.35, 1e-6);
    // Scale multiplies every offset.
    ObjectParams big = east;
    big.scale = 2.0;
    fl = origin(objectNodeToWorld(big, rover, "wheel_fl", flat, 0.0));
    EXPECT_NEAR(fl.x, 20.70, 1e-6);
    EXPECT_NEAR(fl.z, 2.30, 1e-6);
    expectError([&] { objectNodeToWorld(east, rover, "wheel_xx", flat, 0.0); }, {"wheel_xx", model});
}

TEST(Objects, FollowsThePathAndRestsOnSlopedTerrain) {
    // Uphill towards +x (10 %) and +y (5 %): the fitted plane is the terrain itself.
    const Ground slope = planeTerrain(0.1f, 0.05f);
    const std::string model = writeRover();
    const ObjectModel rover = loadGltfModel(model);
    const ObjectParams object = roverObject(model, {{"points", {{20, 20}, {60, 60}}}, {"speed", 1.5}});
    const glm::dvec3 normal = glm::normalize(glm::dvec3(-0.1, -0.05, 1.0));
    for (double time : {0.0, 3.0, 10.0}) {
        const ObjectPose pose = objectPose(object, rover, slope, time);
        const double s = 1.5 * time / std::sqrt(2.0);
        EXPECT_NEAR(pose.position.x, 20.0 + s, 1e-6);
        EXPECT_NEAR(pose.position.y, 20.0 + s, 1e-6);
        EXPECT_NEAR(pose.position.z, slope.height(glm::vec2(pose.position)), 1e-4) << "origin on the ground";
        EXPECT_NEAR(glm::length(pose.up - normal), 0.0, 1e-6) << "up = terrain normal";
        EXPECT_NEAR(glm::dot(pose.forward, pose.up), 0.0, 1e-9);
        // Each wheel hub is one wheel radius above the ground plane: all four wheels touch it.
        for (const char* wheel : {"wheel_fl", "wheel_fr", "wheel_rl", "wheel_rr"}) {
            const glm::dvec3 hub = origin(objectNodeToWorld(object, rover, wheel, slope, time));
            const glm::dvec3 below(hub.x, hub.y, slope.height(glm::vec2(hub)));
            EXPECT_NEAR(glm::dot(hub - below, normal), 0.15, 1e-4) << wheel << " at t=" << time;
        }
    }
    // Not aligned: upright, origin at the terrain height under it.
    ObjectParams upright = object;
    upright.alignToTerrain = false;
    const ObjectPose pose = objectPose(upright, rover, slope, 2.0);
    EXPECT_EQ(pose.up, glm::dvec3(0, 0, 1));
    EXPECT_NEAR(pose.position.z, slope.height(glm::vec2(pose.position)), 1e-5);
}

TEST(Objects, CollidersRideOnTheirNodes) {
    const Ground terrain(makeProceduralTerrain({.size = 100.0f, .spacing = 2.0f, .amplitude = 6.0f}));
    const std::string model = writeRover();
    const nlohmann::json json = nlohmann::json::parse(R"([
        {"name": "a", "model": ")" + model + R"(", "path": {"points": [[30, 30], [70, 40]], "speed": 1}},
        {"name": "b", "model": ")" + model + R"(", "scale": 2, "path": {"points": [[50, 20], [50, 80]], "speed": 2},
         "colliders": [
           {"node": "wheel_fl", "shape": "capsule", "radius": 0.15, "length": 0.12, "axis": "x", "force": 2},
           {"node": "chassis", "shape": "box", "half_extents": [0.2, 0.45, 0.1], "kind": "mower", "cut_height": 0.05},
           {"node": "camera_mount", "shape": "sphere", "radius": 0.1, "offset": [0, -0.5, 0]}
         ]}
    ])");
    const auto objects = parseObjectList(json, "t", "");
    const auto models = loadObjectModels(objects, "t");
    for (double time : {0.0, 4.0}) {
        const auto colliders = objectColliders(objects, models, terrain, time);
        ASSERT_EQ(colliders.size(), 3u);
        EXPECT_EQ(colliders[0].id, 200100u);
        EXPECT_EQ(colliders[1].id, 200101u);
        EXPECT_EQ(colliders[2].id, 200102u);
        // Capsule along the wheel axle (the object's left), centred on the hub, scaled with the object.
        const glm::dmat4 hub = objectNodeToWorld(objects[1], models[1], "wheel_fl", terrain, time);
        const glm::vec3 middle = 0.5f * (colliders[0].centre + colliders[0].end);
        EXPECT_NEAR(glm::distance(middle, glm::vec3(origin(hub))), 0.0f, 1e-4f);
        EXPECT_NEAR(glm::distance(colliders[0].centre, colliders[0].end), 0.24f, 1e-4f);
        const glm::dvec3 left = objectPose(objects[1], models[1], terrain, time).left;
        EXPECT_NEAR(std::abs(glm::dot(glm::normalize(glm::dvec3(colliders[0].end - colliders[0].centre)), left)), 1.0,
                    1e-5);
        EXPECT_FLOAT_EQ(colliders[0].radius, 0.30f);
        EXPECT_FLOAT_EQ(colliders[0].force, 2.0f);
        // Box: the chassis frame, mower kind, half extents scaled.
        EXPECT_EQ(colliders[1].shape, ColliderShape::Box);
        EXPECT_EQ(colliders[1].kind, ColliderKind::Mower);
        EXPECT_FLOAT_EQ(colliders[1].cutHeight, 0.05f);
        EXPECT_NEAR(colliders[1].halfExtents.y, 0.9f, 1e-6f);
        const glm::dmat4 chassis = objectNodeToWorld(objects[1], models[1], "chassis", terrain, time);
        EXPECT_NEAR(glm::distance(colliders[1].centre, glm::vec3(origin(chassis))), 0.0f, 1e-4f);
        EXPECT_NEAR(
            glm::length(glm::dvec3(colliders[1].rotation[2]) - objectPose(objects[1], models[1], terrain, time).up),
            0.0, 1e-5);
        // Offset in the node frame: 0.5 m (x2 scale) ahead of the camera head, i.e. along the heading.
        const glm::dmat4 mount = objectNodeToWorld(objects[1], models[1], "camera_mount", terrain, time);
        const glm::dvec3 ahead = origin(mount) + 2.0 * 0.5 * objectPose(objects[1], models[1], terrain, time).forward;
        EXPECT_NEAR(glm::distance(glm::dvec3(colliders[2].centre), ahead), 0.0, 1e-4);
    }
    // The colliders move with the object: 4 s at 2 m/s north (give or take the hub's sway as the rover tilts).
    const auto c0 = objectColliders(objects, models, terrain, 0.0), c4 = objectColliders(objects, models, terrain, 4.0);
    EXPECT_NEAR(c4[0].centre.y - c0[0].centre.y, 8.0f, 0.05f);
    EXPECT_NEAR(c4[0].centre.x - c0[0].centre.x, 0.0f, 0.05f);
}

TEST(Objects, ParseErrorsNameTheJsonPath) {
    auto bad = [](const char* text, std::initializer_list<std::string> fragments) {
        const nlohmann::json json = nlohmann::json::parse(text);
        expectError([&] { parseObjectList(json, "scene.json", ""); }, fragments);
    };
    bad(R"({"model": "x"})", {"scene.json", "'objects' must be an array"});
    bad(R"([{"path": {"points": [[0, 0]]}}])", {"'objects[0].model' is required"});
    bad(R"([{"model": "x"}])", {"'objects[0].path' is required"});
    bad(R"([{"model": "x", "path": {"points": [[0, 0]]}, "colour": 1}])", {"unknown key 'objects[0].colour'"});
    bad(R"([{"model": "x", "path": {"points": [[0, 0]]}, "scale": 0}])", {"'objects[0].scale' must be between"});
    bad(R"([{"model": "x", "path": {"points": [[0, 0]], "speed": -1}}])", {"'objects[0].path.speed'"});
    bad(R"([{"model": "x", "path": {"points": [[0, 0]]}, "align_to_terrain": 1}])",
        {"'objects[0].align_to_terrain' must be true or false"});
    bad(R"([{"model": "x", "path": {"points": [[0, 0]]}}, {"model": "y", "path": {"points": [[0, 0]]},
           "colliders": [{"node": "a"}, {"node": "b", "radius": -2}]}])",
        {"'objects[1].colliders[1].radius' must be between"});
    bad(R"([{"name": "a", "model": "x", "path": {"points": [[0, 0]]}}, {"name": "a", "model": "x",
           "path": {"points": [[0, 0]]}}])",
        {"'objects[1].name'", "already the name of objects[0]"});
    bad(R"([{"model": "x", "path": {"points": [[0, 0]]}, "colliders": [{"radius": 1}]}])",
        {"'objects[0].colliders[0].node' is required"});
    bad(R"([{"model": "x", "path": {"points": [[0, 0]]}, "colliders": [{"node": "a", "shape": "cone"}]}])",
        {"'objects[0].colliders[0].shape' must be sphere, capsule or box"});
    bad(R"([{"model": "x", "path": {"points": [[0, 0]]}, "colliders": [{"node": "a", "kind": "fell"}]}])",
        {"'objects[0].colliders[0].kind' must be push, gust, downwash or mower"});
    bad(R"([{"model": "x", "path": {"points": [[0, 0]]}, "colliders": [{"node": "a", "half_extents": [1, 2]}]}])",
        {"'objects[0].colliders[0].half_extents' must be an array of 3 numbers"});

    // Model problems surface when the models are loaded, still naming the JSON path.
    const std::string model = writeRover();
    const nlohmann::json json = nlohmann::json::parse(
        R"([{"model": ")" + model +
        R"(", "path": {"points": [[0, 0]]}, "colliders": [{"node": "wheel_fl"}, {"node": "track"}]}])");
    const auto objects = parseObjectList(json, "scene.json", "");
    expectError([&] { loadObjectModels(objects, "scene.json"); },
                {"scene.json", "'objects[0].colliders[1].node'", "no node named 'track'", "wheel_rr"});
    const nlohmann::json missing = parse(R"([{"model": "nowhere.gltf", "path": {"points": [[0, 0]]}}])");
    expectError([&] { loadObjectModels(parseObjectList(missing, "scene.json", "/data"), "scene.json"); },
                {"'objects[0].model'", "/data/nowhere.gltf"});
}

TEST(Objects, SceneReadsObjectsWithModelPathsRelativeToTheSceneFile) {
    const auto dir = tempDir();
    std::filesystem::create_directories(dir / "assets");
    saveRoverGltf((dir / "assets" / "rover.gltf").string());
    {
        std::ofstream scene(dir / "scene.json");
        scene << R"({"terrain": {"size": 100}, "objects": [{"name": "rover", "model": "assets/rover.gltf",
                     "path": {"points": [[10, 10], [90, 90]], "speed": 1},
                     "colliders": [{"node": "wheel_rl", "shape": "capsule", "radius": 0.15}]}]})";
    }
    const Scene scene = loadScene((dir / "scene.json").string());
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].name, "rover");
    EXPECT_EQ(scene.objects[0].model, (dir / "assets" / "rover.gltf").string());
    const auto models = loadObjectModels(scene.objects, scene.source);
    EXPECT_EQ(objectColliders(scene.objects, models, buildTerrain(scene), 1.0).size(), 1u);
    EXPECT_EQ(objectLabel(0), (8u << 24) | 16000000u);
    EXPECT_EQ(objectInstanceId(3), 16000003u);
    EXPECT_TRUE(parseScene(nlohmann::json::object(), "<built-in>").objects.empty());
}

TEST(Objects, MirroredNodesKeepOutwardFacesAndFileWithoutNormalsGetsFlatOnes) {
    // One triangle (glTF y = 0 plane, counter-clockwise seen from +Y) under a node mirrored in x.
    const auto dir = tempDir();
    std::vector<uint8_t> bytes(36);
    const float positions[9] = {0, 0, 0, 0, 0, 1, 1, 0, 0}; // (0,0,0), (0,0,1), (1,0,0): normal +Y
    std::memcpy(bytes.data(), positions, sizeof positions);
    const std::string path = (dir / "mirror.gltf").string();
    {
        std::ofstream file(path);
        file << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
            "nodes": [{"name": "plain", "mesh": 0}, {"name": "mirrored", "mesh": 0, "scale": [-1, 1, 1]}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                           "min": [0, 0, 0], "max": [1, 0, 1]}],
            "bufferViews": [{"buffer": 0, "byteLength": 36}],
            "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)"
             << sward::test::base64(bytes) << R"("}]})";
    }
    const ObjectModel model = loadGltfModel(path);
    ASSERT_EQ(model.nodes.size(), 2u);
    for (const ModelNode& node : model.nodes) {
        const ModelPrimitive& prim = node.primitives.at(0);
        ASSERT_EQ(prim.indices.size(), 3u);
        EXPECT_EQ(prim.normals.at(0), glm::vec3(0, 0, 1)) << node.name; // glTF +Y is sward's +z
        // In the model frame the triangle must face up (+z) for both nodes.
        glm::dvec3 p[3];
        for (int i = 0; i < 3; ++i)
            p[i] =
                glm::dvec3(node.modelFromNode * glm::dvec4(glm::dvec3(prim.positions[prim.indices[size_t(i)]]), 1.0));
        EXPECT_GT(glm::cross(p[1] - p[0], p[2] - p[0]).z, 0.0) << node.name;
    }
    EXPECT_EQ(model.boundsMin, glm::vec3(-1, -1, 0));
    EXPECT_EQ(model.boundsMax, glm::vec3(1, 0, 0));
}

TEST(Objects, SharedOrCyclicNodesAreRejected) {
    // Node 1 listed twice as a child: not a tree (and, nested, an exponential walk in a hostile file).
    const auto dir = tempDir();
    std::vector<uint8_t> bytes(36, 0);
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 0, 1};
    std::memcpy(bytes.data(), positions, sizeof positions);
    const std::string path = (dir / "shared.gltf").string();
    std::ofstream(path) << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "root", "children": [1, 1]}, {"name": "leaf", "mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 0, 1]}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)"
                        << sward::test::base64(bytes) << R"("}]})";
    expectError([&] { loadGltfModel(path); }, {path, "node 1 is used more than once"});
    expectError([&] { loadGltfMesh(path); }, {path, "node 1 is used more than once"});
}

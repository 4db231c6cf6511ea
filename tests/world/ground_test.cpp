#include "world/gltf_mesh.h"
#include "world/ground.h"
#include "io/image_io.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <cstring>

using namespace sward;
using namespace sward::test;

namespace {

// Writes a glTF (Y-up) with one quad [0,10] x [0,10] in glTF x/-z whose height y = 0.1 * x + 0.2 * (-z) + 1,
// translated by the node, with an embedded base64 buffer.
std::string writeSlopeGltf(const std::filesystem::path& dir, const char* mode = "4") {
    const float positions[4][3] = {{0, 1, 0}, {10, 2, 0}, {10, 4, -10}, {0, 3, -10}};
    const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
    std::vector<uint8_t> bytes(sizeof positions + sizeof indices);
    std::memcpy(bytes.data(), positions, sizeof positions);
    std::memcpy(bytes.data() + sizeof positions, indices, sizeof indices);
    const std::string json = R"({
      "asset": {"version": "2.0"},
      "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0, "translation": [100, 0, -200]}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": )" +
                             std::string(mode) + R"(}]}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0,1,-10], "max": [10,4,0]},
        {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
      "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,)" +
                             base64(bytes) + R"("}]
    })";
    const auto path = dir / "slope.gltf";
    std::ofstream(path) << json;
    return path.string();
}

} // namespace

TEST(Ground, GltfMeshIsConvertedToZUpWithNodeTransform) {
    const TriangleMesh mesh = loadGltfMesh(writeSlopeGltf(tempDir()));
    ASSERT_EQ(mesh.indices.size(), 6u);
    EXPECT_EQ(mesh.positions[2], glm::vec3(110.0f, 210.0f, 4.0f)); // glTF (10, 4, -10) + (100, 0, -200)
}

TEST(Ground, MeshSurfaceInterpolatesTheTriangleUnderXy) {
    const Ground ground(loadGltfMesh(writeSlopeGltf(tempDir())));
    const auto s = ground.surface({105.0f, 202.5f});
    ASSERT_TRUE(s.has_value());
    EXPECT_NEAR(s->height, 1.0f + 0.1f * 5.0f + 0.2f * 2.5f, 1e-5f);
    EXPECT_NEAR(glm::length(s->normal - glm::normalize(glm::vec3(-0.1f, -0.2f, 1.0f))), 0.0f, 1e-5f);
    EXPECT_FALSE(ground.surface({99.0f, 205.0f}).has_value()); // off the mesh
}

TEST(Ground, MeshSurfaceTakesTheTopMostLayer) {
    TriangleMesh mesh{{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 2}, {4, 0, 2}, {0, 4, 2}}, {0, 1, 2, 3, 5, 4}};
    EXPECT_EQ(Ground(mesh).surface({1.0f, 1.0f})->height, 2.0f);
    EXPECT_GT(Ground(mesh).surface({1.0f, 1.0f})->normal.z, 0.0f); // the second triangle winds clockwise
}

TEST(Ground, HeightfieldGroundEndsAtTheGridEdge) {
    const Ground ground(makeProceduralTerrain({.size = 50.0f, .spacing = 5.0f}));
    EXPECT_TRUE(ground.surface({50.0f, 0.0f}).has_value());
    EXPECT_FALSE(ground.surface({50.01f, 10.0f}).has_value());
}

TEST(GroundErrors, GltfStripPrimitivesAreRejectedNamingTheFile) {
    const auto path = writeSlopeGltf(tempDir(), "5");
    expectError([&] { loadGltfMesh(path); }, {path, "primitive mode 5"});
}

TEST(GroundErrors, MissingGltfNamesTheFile) {
    const auto path = (tempDir() / "absent.gltf").string();
    expectError([&] { loadGltfMesh(path); }, {path});
}


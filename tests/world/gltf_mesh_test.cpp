// glTF files from untrusted scenes: sizes that would wrap a bounds check, non-finite transforms and vertices,
// required extensions, and buffer files that must neither escape the scene's folder nor leak into messages.
#include "world/gltf_mesh.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

using namespace sward;
using namespace sward::test;

namespace fs = std::filesystem;

namespace {

// One triangle: POSITION (3 x VEC3 float, bytes 0..35) and uint32 indices 0, 1, 2 (bytes 36..47) in buffer 0.
nlohmann::json triangleJson(const std::string& uri, size_t byteLength = 48) {
    nlohmann::json j = nlohmann::json::parse(R"({
      "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0, "name": "body"}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                    {"bufferView": 1, "componentType": 5125, "count": 3, "type": "SCALAR"}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                      {"buffer": 0, "byteOffset": 36, "byteLength": 12}]})");
    j["buffers"] = {{{"byteLength", byteLength}, {"uri", uri}}};
    return j;
}

std::vector<uint8_t> triangleBytes(float x1 = 1.0f) {
    const float positions[9] = {0, 0, 0, x1, 0, 0, 0, 0, 1};
    const uint32_t indices[3] = {0, 1, 2};
    std::vector<uint8_t> bytes(48);
    std::memcpy(bytes.data(), positions, 36);
    std::memcpy(bytes.data() + 36, indices, 12);
    return bytes;
}

void writeBytes(const fs::path& path, const std::vector<uint8_t>& bytes) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

std::string writeJson(const fs::path& path, const nlohmann::json& json) {
    std::ofstream(path) << json.dump();
    return path.string();
}

// A triangle glTF with its buffer embedded, after `edit` changed its JSON.
template <class Edit> std::string writeEdited(const fs::path& dir, Edit edit) {
    nlohmann::json j = triangleJson("data:application/octet-stream;base64," + base64(triangleBytes()));
    edit(j);
    return writeJson(dir / "m.gltf", j);
}

// Runs both loaders on `path`, expecting a sward::Error with every fragment from each.
void expectBothFail(const std::string& path, std::initializer_list<std::string> fragments,
                    const AssetPolicy& assets = {}) {
    expectError([&] { loadGltfMesh(path, assets); }, fragments);
    expectError([&] { loadGltfModel(path, assets); }, fragments);
}

std::string messageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

} // namespace

TEST(GltfMesh, ExternalBufferInTheFolderLoads) {
    const fs::path dir = fs::canonical(tempDir());
    writeBytes(dir / "m.bin", triangleBytes());
    const std::string path = writeJson(dir / "m.gltf", triangleJson("m.bin"));
    const AssetPolicy confined = AssetPolicy::confinedTo(dir.string(), {});
    EXPECT_EQ(loadGltfMesh(path, confined).indices.size(), 3u);
    EXPECT_EQ(loadGltfModel(path, confined).triangleCount(), 1u);
}

// 2^62 uint32 indices: 4 * (2^62 - 1) + 4 wraps to 0 in 64 bits, which passed the old check and read past the
// buffer (AddressSanitizer: heap-buffer-overflow).
// tinygltf takes the first byte of a .glb it is handed: an empty file threw std::out_of_range from inside it (found
// by fuzz_glb, fuzz/regressions/glb/empty-file). The door's reader refuses it first.
TEST(GltfMeshErrors, AnEmptyFileIsOneClearError) {
    const fs::path dir = test::tempDir();
    for (const char* name : {"m.glb", "m.gltf"}) {
        std::ofstream(dir / name).close();
        expectBothFail((dir / name).string(), {name, "is empty"});
    }
}

TEST(GltfMeshErrors, AccessorCountNear2To62IsRefusedBeforeAnyRead) {
    const fs::path dir = tempDir();
    const std::string indices = writeEdited(dir, [](nlohmann::json& j) { j["accessors"][1]["count"] = 1ull << 62; });
    expectBothFail(indices, {"accessor 1 (4611686018427387904 elements) reaches past the end of buffer view 1"});
    const std::string positions =
        writeEdited(dir, [](nlohmann::json& j) { j["accessors"][0]["count"] = (1ull << 62) + 1; });
    expectBothFail(positions, {"accessor 0 (4611686018427387905 elements) reaches past the end of buffer view 0"});
}

TEST(GltfMeshErrors, OffsetsThatWouldWrapAreRefused) {
    const fs::path dir = tempDir();
    const std::string view = writeEdited(dir, [](nlohmann::json& j) {
        j["bufferViews"][1]["byteOffset"] = 36;
        j["bufferViews"][1]["byteLength"] = UINT64_MAX - 20; // offset + length wraps to 15
    });
    expectBothFail(view, {"buffer view 1 reaches past the end of its buffer"});
    const std::string accessor =
        writeEdited(dir, [](nlohmann::json& j) { j["accessors"][1]["byteOffset"] = UINT64_MAX - 3; });
    expectBothFail(accessor, {"accessor 1 starts past the end of its buffer view"});
}

TEST(GltfMeshErrors, HugeNodeScaleIsRefusedNamingTheNode) {
    const std::string path = writeEdited(tempDir(), [](nlohmann::json& j) { j["nodes"][0]["scale"] = {1e308, 1, 1}; });
    expectBothFail(path, {"node 0 ('body'): 'scale' holds a value beyond 1e8 (or not finite)"});
    const std::string matrix = writeEdited(tempDir(), [](nlohmann::json& j) {
        j["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1e300, 0, 1};
    });
    expectBothFail(matrix, {"node 0 ('body'): 'matrix' holds a value beyond 1e8"});
}

TEST(GltfMeshErrors, HugeParentScaleIsRefusedOnTheComposedTransform) {
    const std::string path = writeEdited(tempDir(), [](nlohmann::json& j) {
        j["scenes"][0]["nodes"] = {1};
        j["nodes"].push_back({{"name", "parent"}, {"scale", {1e5, 1e5, 1e5}}, {"children", {0}}});
        j["nodes"][0]["scale"] = {1e5, 1e5, 1e5}; // each fine alone, 1e10 together
    });
    expectBothFail(path,
                   {"node 0 ('body'): its transform (with its parents') is not finite or has an entry beyond 1e8"});
}

TEST(GltfMeshErrors, NonFinitePositionsAreRefused) {
    const fs::path dir = tempDir();
    nlohmann::json j = triangleJson("data:application/octet-stream;base64," +
                                    base64(triangleBytes(std::numeric_limits<float>::quiet_NaN())));
    expectBothFail(writeJson(dir / "nan.gltf", j), {"accessor 0 (POSITION): element 1 is not finite"});
    j["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(triangleBytes(3e38f));
    expectBothFail(writeJson(dir / "far.gltf", j), {"accessor 0 (POSITION): element 1 is not finite or beyond 1e8 m"});
}

TEST(GltfMeshErrors, IndicesPastTheVertexCountAreRefused) {
    const std::string path = writeEdited(tempDir(), [](nlohmann::json& j) { j["accessors"][0]["count"] = 2; });
    expectBothFail(path, {"accessor 1 (indices): element 2 is not below the vertex count 2"});
}

TEST(GltfMeshErrors, DracoCompressionIsNamedWithTheFix) {
    // A Draco file's accessors have no buffer view: tinygltf alone says "accessor[0] invalid bufferView".
    const std::string path = writeEdited(tempDir(), [](nlohmann::json& j) {
        j["extensionsUsed"] = {"KHR_draco_mesh_compression"};
        j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
        j["accessors"][0].erase("bufferView");
        j["accessors"][1].erase("bufferView");
    });
    expectBothFail(path, {"m.gltf': uses KHR_draco_mesh_compression, which sward does not support; export without "
                          "Draco compression"});
}

TEST(GltfMeshErrors, AnyOtherRequiredExtensionIsRefused) {
    const std::string path =
        writeEdited(tempDir(), [](nlohmann::json& j) { j["extensionsRequired"] = {"KHR_mesh_quantization"}; });
    expectBothFail(path, {"uses KHR_mesh_quantization (extensionsRequired), which sward does not support"});
}

TEST(GltfMeshErrors, BufferUriOutsideTheSceneFolderIsRefused) {
    const fs::path root = fs::canonical(tempDir());
    fs::create_directories(root / "scene");
    fs::create_directories(root / "outside");
    writeBytes(root / "outside" / "t.bin", triangleBytes());
    fs::create_symlink(root / "outside" / "t.bin", root / "scene" / "link.bin");
    const AssetPolicy confined = AssetPolicy::confinedTo((root / "scene").string(), {});
    for (const std::string& uri : {std::string("../outside/t.bin"), (root / "outside" / "t.bin").string(),
                                   std::string("link.bin"), std::string("/etc/passwd")}) {
        const std::string path = writeJson(root / "scene" / "m.gltf", triangleJson(uri));
        expectBothFail(path, {"m.gltf': buffer uri: '" + uri + "' resolves to ", "outside the scene's folder"},
                       confined);
    }
    // Allowed: the same files load.
    const AssetPolicy allowed = AssetPolicy::confinedTo((root / "scene").string(), {(root / "outside").string()});
    for (const std::string& uri : {std::string("../outside/t.bin"), std::string("link.bin")}) {
        const std::string path = writeJson(root / "scene" / "m.gltf", triangleJson(uri));
        EXPECT_EQ(loadGltfModel(path, allowed).triangleCount(), 1u) << uri;
    }
}

TEST(GltfMeshErrors, BufferFileErrorsQuoteNeitherItsSizeNorItsBytes) {
    // A file the glTF names but that is no glTF buffer: 1000 bytes of 0x41 ('A').
    const fs::path dir = tempDir();
    writeBytes(dir / "secret.txt", std::vector<uint8_t>(1000, 0x41));
    // byteLength differs from the file's size: tinygltf's own message states the size.
    const std::string wrongSize = writeJson(dir / "m.gltf", triangleJson("secret.txt"));
    for (const std::string& message :
         {messageOf([&] { loadGltfMesh(wrongSize); }), messageOf([&] { loadGltfModel(wrongSize); })}) {
        EXPECT_NE(message.find("the file of buffer uri 'secret.txt' is not byteLength bytes long"), std::string::npos)
            << message;
        EXPECT_EQ(message.find("1000"), std::string::npos) << message;
    }
    // byteLength matches: the positions read as 'AAAA' floats (finite), the indices as 0x41414141.
    nlohmann::json j = triangleJson("secret.txt", 1000);
    const std::string matching = writeJson(dir / "m.gltf", j);
    for (const std::string& message :
         {messageOf([&] { loadGltfMesh(matching); }), messageOf([&] { loadGltfModel(matching); })}) {
        EXPECT_NE(message.find("accessor 1 (indices): element 0 is not below the vertex count 3"), std::string::npos)
            << message;
        EXPECT_EQ(message.find(std::to_string(0x41414141u)), std::string::npos) << message;
    }
}

// One mesh of 1,000 triangles under 20,000 nodes flattens to 2 x 10^7: priced from the accessors' counts before a
// vertex is copied (100,000 nodes over a 1.5 MB mesh had no frame after 600 s).
TEST(GltfMeshErrors, InstancesTimesTrianglesArePricedBeforeTheMeshIsFlattened) {
    const fs::path dir = tempDir();
    std::vector<uint8_t> bytes = triangleBytes();
    bytes.resize(36 + 3000 * 4, 0); // 3,000 indices, all vertex 0
    nlohmann::json j = triangleJson("data:application/octet-stream;base64," + base64(bytes), bytes.size());
    j["accessors"][1]["count"] = 3000;
    j["bufferViews"][1]["byteLength"] = 3000 * 4;
    j["nodes"] = nlohmann::json::array();
    j["scenes"][0]["nodes"] = nlohmann::json::array();
    for (int i = 0; i < 20000; ++i) {
        j["nodes"].push_back({{"mesh", 0}});
        j["scenes"][0]["nodes"].push_back(i);
    }
    const std::string path = writeJson(dir / "many.gltf", j);
    expectError([&] { loadGltfMesh(path); },
                {path, "20000 mesh instances (nodes) would flatten into 20000000 triangles and 60000 vertices, over "
                       "the limit of 16777216 of each"});
}

// 20 materials over one 8192^2 image took 5.9 GB: textures that share an image share one decoded copy.
TEST(GltfMesh, TexturesThatShareAnImageAreDecodedOnce) {
    const fs::path dir = fs::canonical(tempDir());
    writePng(dir / "tex.png", 2, 2, 3, 8, std::vector<float>(12, 0.5f));
    std::vector<uint8_t> bytes = triangleBytes();
    const float uvs[6] = {0, 0, 1, 0, 0, 1};
    bytes.insert(bytes.end(), reinterpret_cast<const uint8_t*>(uvs), reinterpret_cast<const uint8_t*>(uvs) + 24);
    nlohmann::json j = triangleJson("data:application/octet-stream;base64," + base64(bytes), bytes.size());
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 24}});
    j["accessors"].push_back({{"bufferView", 2}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}});
    j["images"] = {{{"uri", "tex.png"}}};
    j["textures"] = nlohmann::json::array();
    j["materials"] = nlohmann::json::array();
    j["meshes"][0]["primitives"] = nlohmann::json::array();
    for (int i = 0; i < 3; ++i) {
        j["textures"].push_back({{"source", 0}});
        j["materials"].push_back(
            {{"name", "m" + std::to_string(i)}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", i}}}}}});
        j["meshes"][0]["primitives"].push_back(
            {{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 2}}}, {"indices", 1}, {"material", i}});
    }
    const std::string path = writeJson(dir / "textured.gltf", j);
    const TriangleMesh mesh = loadGltfMesh(path, AssetPolicy::confinedTo(dir.string(), {}));
    ASSERT_EQ(mesh.materials.size(), 3u);
    EXPECT_EQ(mesh.textures.size(), 1u);
    for (const GroundMaterial& m : mesh.materials) EXPECT_EQ(m.texture, 0);
}

// Embedded images are kept as PNG bytes at load and decoded only when a material uses them, once: an unused image
// whose header claims 16384^2 costs nothing.
TEST(GltfMesh, EmbeddedImagesAreDecodedOnlyWhenUsed) {
    const fs::path dir = fs::canonical(tempDir());
    writePng(dir / "tex.png", 2, 1, 3, 8, {1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f});
    std::ifstream in(dir / "tex.png", std::ios::binary);
    const std::vector<uint8_t> png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<uint8_t> huge = png;
    for (size_t at : {16u, 20u}) huge[at] = 0, huge[at + 1] = 0, huge[at + 2] = 0x40, huge[at + 3] = 0; // 16384
    std::vector<uint8_t> bytes = triangleBytes();
    const float uvs[6] = {0, 0, 1, 0, 0, 1};
    bytes.insert(bytes.end(), reinterpret_cast<const uint8_t*>(uvs), reinterpret_cast<const uint8_t*>(uvs) + 24);
    nlohmann::json j = triangleJson("data:application/octet-stream;base64," + base64(bytes), bytes.size());
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 24}});
    j["accessors"].push_back({{"bufferView", 2}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}});
    j["images"] = {{{"uri", "data:image/png;base64," + base64(huge)}},
                   {{"uri", "data:image/png;base64," + base64(png)}}};
    j["textures"] = {{{"source", 1}}, {{"source", 1}}};
    j["materials"] = {{{"name", "a"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}},
                      {{"name", "b"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 1}}}}}}};
    const nlohmann::json primitive = j["meshes"][0]["primitives"][0];
    j["meshes"][0]["primitives"] = nlohmann::json::array();
    for (int i = 0; i < 2; ++i) {
        nlohmann::json p = primitive;
        p["attributes"]["TEXCOORD_0"] = 2;
        p["material"] = i;
        j["meshes"][0]["primitives"].push_back(p);
    }
    const TriangleMesh mesh = loadGltfMesh(writeJson(dir / "embedded.gltf", j));
    ASSERT_EQ(mesh.textures.size(), 1u);
    EXPECT_EQ(mesh.textures[0].width, 2u);
    EXPECT_EQ(mesh.textures[0].rgba, (std::vector<uint8_t>{255, 0, 0, 255, 0, 0, 255, 255}));
}

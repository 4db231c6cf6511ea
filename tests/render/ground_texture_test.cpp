// A textured glTF ground: the material's baseColorTexture (an external PNG) is drawn, mapped by TEXCOORD_0 as
// glTF defines it (uv (0, 0) at the image's top-left). The texture is red on its left (west) half and blue on its
// right (east) half; every ground pixel's world position comes from an independent ray cast.
#include "gpu_test.h"
#include "test_files.h"

#include "common/half_float.h"
#include "render/scene_gpu.h"
#include "scene/scene_resources.h"

#include <cstring>
#include <fstream>

using namespace sward;
using sward::test::GpuTest;

namespace {

constexpr uint32_t kWidth = 160, kHeight = 120;

// A 20 x 20 m quad (glTF x / -z) with uv = (x / 20, 1 - north / 20), so the image's top row is the north edge.
std::string writeTexturedGround(const std::filesystem::path& dir) {
    const float positions[4][3] = {{0, 0, 0}, {20, 0, 0}, {20, 0, -20}, {0, 0, -20}};
    const float uvs[4][2] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
    std::vector<uint8_t> bytes(sizeof positions + sizeof uvs + sizeof indices);
    std::memcpy(bytes.data(), positions, sizeof positions);
    std::memcpy(bytes.data() + sizeof positions, uvs, sizeof uvs);
    std::memcpy(bytes.data() + sizeof positions + sizeof uvs, indices, sizeof indices);
    std::vector<float> texels; // 8 x 4 RGB: left half red, right half blue
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) texels.insert(texels.end(), {x < 4 ? 1.0f : 0.0f, 0.0f, x < 4 ? 0.0f : 1.0f});
    sward::test::writePng(dir / "texture.png", 8, 4, 3, 8, texels);
    std::ofstream(dir / "ground.gltf") << R"({
      "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
      "materials": [{"name": "painted", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
      "textures": [{"source": 0}], "images": [{"uri": "texture.png"}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0,0,-20], "max": [20,0,0]},
        {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
        {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                      {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
      "buffers": [{"byteLength": 92, "uri": "data:application/octet-stream;base64,)" +
                                       sward::test::base64(bytes) + R"("}]})";
    std::ofstream(dir / "scene.json") << R"({
      "terrain": {"mesh": {"file": "ground.gltf"}}, "vegetation_enabled": false,
      "camera": {"position": [10, -4, 0], "height_above_ground": 14, "look_at": [10, 10, 0], "fov_y_deg": 60},
      "render": {"shadow_map_size": 0}})";
    return (dir / "scene.json").string();
}

} // namespace

class GroundTextureTest : public GpuTest {};

TEST_F(GroundTextureTest, BaseColorTextureIsDrawnWhereItsUvsPutIt) {
    SceneResources resources = buildSceneResources(loadScene(writeTexturedGround(sward::test::tempDir())), true, 1);
    ASSERT_EQ(resources.terrain.mesh()->textures.size(), 1u);
    const Camera camera = sceneCamera(resources.scene, resources.terrain, kWidth, kHeight);
    SceneGpu gpu = createSceneGpu(*ctx, resources, 1, SimulationMode::None);
    const FrameImages frame = renderFrame(*ctx, *gpu.renderer, camera);
    uint32_t red = 0, blue = 0;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const auto hit =
                resources.terrain.raycast(camera.position, glm::normalize(camera.ray(x + 0.5, y + 0.5)), 1000.0);
            if (!hit) continue;
            const glm::dvec3 p = camera.position + *hit * glm::normalize(camera.ray(x + 0.5, y + 0.5));
            if (p.y < 1.0 || p.y > 19.0 || std::abs(p.x - 10.0) < 1.5 || p.x < 1.0 || p.x > 19.0) continue;
            const size_t i = (size_t(y) * kWidth + x) * 4;
            const float r = halfBitsToFloat(frame.rgbaHalf[i]), b = halfBitsToFloat(frame.rgbaHalf[i + 2]);
            if (p.x < 10.0) {
                ASSERT_GT(r, 4.0f * b) << "west pixel " << x << ", " << y << " is not red";
                ++red;
            } else {
                ASSERT_GT(b, 4.0f * r) << "east pixel " << x << ", " << y << " is not blue";
                ++blue;
            }
        }
    EXPECT_GT(red, 500u);
    EXPECT_GT(blue, 500u);
}

TEST(GroundTextureErrors, ANonPngTextureIsRefusedNamingTheImage) {
    const auto dir = sward::test::tempDir();
    const std::string scene = writeTexturedGround(dir);
    std::ofstream(dir / "texture.png", std::ios::trunc) << "\xff\xd8\xff\xe0 not a png, a JPEG header";
    sward::test::expectError([&] { buildSceneResources(loadScene(scene), false, 1); },
                             {"'terrain.mesh'", "image 0 is not a PNG"});
}

// Scene objects on the GPU (vegetation/render/object_renderer.h): the default rover drawn on its own into the
// main, truth and shadow passes, checked against its analytic geometry: visible where projected, exact planar
// depth, the object label, the faces' normals, and the shadow of a second object falling on it.
#include "common/half_float.h"
#include "gpu_test.h"
#include "plate_gltf.h"

#include "io/image_files.h"
#include "render/object_renderer.h"
#include "scene/rover_model.h"
#include "render/scene_renderer.h"
#include "render/sky_constants.h"

#include "shared/gpu_layout.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>

using namespace sward;
using sward::test::GpuTest;
using sward::test::tempDir;
using sward::test::writePlate;

namespace {

constexpr uint32_t kWidth = 160, kHeight = 120;
constexpr float kGround = 1.0f;

// A 3 m x 3 m two-sided plate (glTF y = 0 plane), to cast a shadow.
struct Images {
    std::vector<uint16_t> color;
    std::vector<uint32_t> depthBits, labels;
    std::vector<glm::vec4> normals; // the truth pass's camera-frame normal per pixel, w unused
    glm::vec3 rgb(glm::ivec2 p) const {
        const size_t i = (size_t(p.y) * kWidth + size_t(p.x)) * 4;
        return {halfBitsToFloat(color[i]), halfBitsToFloat(color[i + 1]), halfBitsToFloat(color[i + 2])};
    }
    float depth(glm::ivec2 p) const {
        float d;
        std::memcpy(&d, &depthBits[size_t(p.y) * kWidth + size_t(p.x)], 4);
        return d;
    }
    uint32_t label(glm::ivec2 p) const { return labels[size_t(p.y) * kWidth + size_t(p.x)]; }
    glm::dvec3 normal(glm::ivec2 p) const { return glm::dvec3(normals[size_t(p.y) * kWidth + size_t(p.x)]); }
};

class ObjectRenderTest : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        dir = tempDir("objects");
        saveRoverGltf(dir + "/rover.gltf");
        writePlate(dir);
    }

    // The rover drives east from (50, 50); with `plate`, a plate hovers 1.2 m above it. Sun from the south, 70
    // degrees up. Camera south of the rover, looking north and down at it.
    Images render(bool plate) {
        nlohmann::json objects = nlohmann::json::array();
        objects.push_back(
            {{"name", "rover"}, {"model", "rover.gltf"}, {"path", {{"points", {{50, 50}, {60, 50}}}, {"speed", 1}}}});
        if (plate)
            objects.push_back({{"model", "plate.gltf"},
                               {"align_to_terrain", false},
                               {"path", {{"points", {{50, 50}}}, {"height_above_ground", 1.2}}}});
        const Scene scene = parseScene({{"sun", {{"azimuth_deg", 180}, {"elevation_deg", 70}}}, {"objects", objects}},
                                       dir + "/scene.json");
        const VegetationPassFormats formats{.mainColor = VK_FORMAT_R16G16B16A16_SFLOAT,
                                            .mainDepth = VK_FORMAT_D32_SFLOAT,
                                            .mainSamples = VK_SAMPLE_COUNT_1_BIT,
                                            .truthDepthBits = VK_FORMAT_R32_UINT,
                                            .truthLabel = VK_FORMAT_R32G32_UINT,
                                            .truthNormal = VK_FORMAT_R32G32B32A32_SFLOAT,
                                            .truthDepth = VK_FORMAT_D32_SFLOAT,
                                            .shadowDepth = VK_FORMAT_D32_SFLOAT};
        ObjectRenderer objectRenderer(*ctx, scene, terrain, formats);
        EXPECT_GE(objectRenderer.triangleCount(), 300u);
        objectRenderer.update(0.0, 1);

        // Frame constants as SceneRenderer writes them, with a 10 m orthographic shadow box around the rover.
        gpu::FrameConstants c{};
        c.viewProj = glm::mat4(camera.viewProjection());
        c.view = glm::mat4(camera.view());
        c.invViewProj = glm::mat4(glm::inverse(camera.viewProjection()));
        c.cameraPosition = glm::vec4(glm::vec3(camera.position), 1.0f);
        c.sunDirection = glm::vec4(scene.sun.direction(), 0.0f);
        c.sunRadiance = glm::vec4(scene.sun.radiance, 0.0f);
        writeSkyConstants(scene, c);
        c.viewport = glm::vec4(kWidth, kHeight, 1.0f / kWidth, 1.0f / kHeight);
        const double radius = 5.0, reach = 20.0, size = 512.0;
        const glm::dmat4 lightView =
            glm::lookAt(glm::dvec3(0.0), -glm::dvec3(scene.sun.direction()), glm::dvec3(0, 0, 1));
        const glm::dvec4 centre = lightView * glm::dvec4(50.0, 50.0, 1.5, 1.0);
        glm::dmat4 ortho(0.0);
        ortho[0][0] = ortho[1][1] = 1.0 / radius;
        ortho[2][2] = 1.0 / (2.0 * reach);
        ortho[3] = glm::dvec4(-centre.x / radius, -centre.y / radius, 0.5 - centre.z / (2.0 * reach), 1.0);
        c.shadowViewProj = glm::mat4(ortho * lightView); // one cascade reaching far beyond the scene
        c.shadowCascades[0] = c.shadowViewProj;
        c.shadowParams = glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
        c.shadowTiles[0] = glm::vec4(0.0f, 1.0f, 1.0f, float(1.0 / size));
        c.shadowEnds = glm::vec4(1e6f);
        c.shadowBias = glm::vec4(float(0.05 / (2.0 * reach)));
        c.shadowOrigin = c.cameraPosition;
        Buffer constants = createBuffer(*ctx, sizeof c, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryIntent::Upload);
        std::memcpy(constants.mapped(), &c, sizeof c);

        RenderTarget shadow(*ctx, RenderTargetDesc{.width = uint32_t(size),
                                                   .height = uint32_t(size),
                                                   .depthFormat = VK_FORMAT_D32_SFLOAT,
                                                   .sampleDepth = true});
        VkSamplerCreateInfo samplerInfo{.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
                                        .magFilter = VK_FILTER_LINEAR,
                                        .minFilter = VK_FILTER_LINEAR,
                                        .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                                        .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                                        .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                                        .compareEnable = VK_TRUE,
                                        .compareOp = VK_COMPARE_OP_GREATER_OR_EQUAL};
        VkSampler sampler = VK_NULL_HANDLE;
        VK_CHECK(vkCreateSampler(ctx->vk(), &samplerInfo, nullptr, &sampler));
        RenderTarget main(*ctx, mainPassTargetDesc(kWidth, kHeight, 1));
        RenderTarget truth(*ctx, truthPassTargetDesc(kWidth, kHeight));

        const DescriptorBinding frame = uniformBuffer(0, constants.handle, 0, sizeof c);
        const DescriptorBinding shadowMap =
            sampledImage(5, shadow.depth().view, sampler, VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL);
        ctx->submitter.immediate([&](VkCommandBuffer cmd) {
            shadow.begin(cmd);
            objectRenderer.recordShadow(cmd, frame, 1);
            shadow.end(cmd);
            main.begin(cmd);
            objectRenderer.recordMain(cmd, frame, shadowMap, 1);
            main.end(cmd);
            truth.begin(cmd);
            objectRenderer.recordTruth(cmd, frame, 1);
            truth.end(cmd);
        });
        Images images;
        auto color = main.readback(0), depth = truth.readback(0), labels = truth.readback(1);
        const auto normals = truth.readback(2);
        images.normals.resize(normals.size() / 16);
        std::memcpy(images.normals.data(), normals.data(), normals.size());
        images.color.resize(color.size() / 2);
        std::memcpy(images.color.data(), color.data(), color.size());
        images.depthBits.resize(depth.size() / 4);
        std::memcpy(images.depthBits.data(), depth.data(), depth.size());
        // (label, tile) pairs: objects have no tile.
        images.labels.resize(labels.size() / 8);
        for (size_t i = 0; i < images.labels.size(); ++i) {
            uint32_t pair[2];
            std::memcpy(pair, labels.data() + 8 * i, 8);
            images.labels[i] = pair[0];
            EXPECT_EQ(pair[1], 0u);
        }
        if (const char* png = std::getenv("SWARD_OBJECT_TEST_PNG")) // for looking at it: a tonemapped preview
            writePng8(std::string(png) + (plate ? "-plate.png" : ".png"), kWidth, kHeight, 3,
                      tonemapPreview(images.color, kWidth, kHeight));
        ctx->submitter.waitIdle();
        vkDestroySampler(ctx->vk(), sampler, nullptr);
        destroyBuffer(*ctx, constants);
        return images;
    }

    // The pixel whose centre sees world point `p`.
    glm::ivec2 pixelOf(glm::dvec3 p) const {
        const glm::dvec3 uv = camera.project(p);
        return {int(std::floor(uv.x)), int(std::floor(uv.y))};
    }

    std::string dir;
    Ground terrain{Heightfield{51, 51, 2.0f, glm::vec2(0.0f), std::vector<float>(51 * 51, kGround)}};
    Camera camera = Camera::lookAt({50.0, 47.5, 2.0}, {50.0, 50.0, 1.2}, {0, 0, 1}, 50.0, kWidth, kHeight);
};

float luminance(glm::vec3 c) {
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

} // namespace

TEST_F(ObjectRenderTest, RoverIsDrawnWithExactDepthAndItsLabel) {
    const Images images = render(false);
    const uint32_t rover = (gpu::kSemanticObject << gpu::kInstanceBits) | gpu::kInstanceObjectBase;
    ASSERT_EQ(rover, objectLabel(0));

    // The chassis' right side (the rover heads east, so its right faces the camera in the south) is the plane
    // y = 50 - 0.22 between the wheels; the truth depth at the pixel is that plane's, along the pixel's ray.
    const double side = 50.0 - 0.22;
    const glm::ivec2 p = pixelOf({50.0, side, kGround + 0.22});
    const glm::dvec3 ray = camera.ray(p.x + 0.5, p.y + 0.5);
    const double planar = (side - camera.position.y) / ray.y;
    const glm::dvec3 hit = camera.position + planar * ray;
    ASSERT_NEAR(hit.z, kGround + 0.22, 0.05) << "the test pixel must lie on the body side";
    EXPECT_EQ(images.label(p), rover);
    EXPECT_NEAR(images.depth(p), planar, 1e-3);
    const glm::vec3 body = images.rgb(p);
    EXPECT_GT(body.r, 1.5f * body.g) << "the body is orange";
    EXPECT_GT(body.g, body.b);

    // A wheel's outer face: the same label, a dark tyre or grey hub, nearer than the body side.
    const glm::ivec2 wheel = pixelOf({50.35 + 0.11, 50.0 - 0.35, kGround + 0.15}); // on the front-right tyre wall
    EXPECT_EQ(images.label(wheel), rover);
    EXPECT_LT(images.depth(wheel), images.depth(p));

    // Nothing else was drawn: cleared colour, +inf depth, the sky label.
    for (glm::ivec2 q : {glm::ivec2(0, 0), glm::ivec2(kWidth - 1, 0), glm::ivec2(0, kHeight - 1),
                         glm::ivec2(kWidth - 1, kHeight - 1)}) {
        EXPECT_EQ(images.depthBits[size_t(q.y) * kWidth + size_t(q.x)], gpu::kDepthInfinityBits);
        EXPECT_EQ(images.label(q), gpu::kSemanticSky << gpu::kInstanceBits);
        EXPECT_EQ(images.rgb(q), glm::vec3(0.0f));
    }
    // The rover covers a plausible part of the image: about 1 m wide at 2.6 m with f = 129 px.
    size_t covered = 0;
    for (uint32_t label : images.labels) covered += label == rover;
    EXPECT_GT(covered, size_t(kWidth * kHeight / 20));
    EXPECT_LT(covered, size_t(kWidth * kHeight / 2));
}

TEST_F(ObjectRenderTest, SecondObjectShadowsTheRoverAndHasItsOwnLabel) {
    // The deck top, lit by the high sun, falls into the hovering plate's shadow once the plate is there.
    const glm::dvec3 deck(50.0 - 0.03, 50.0, kGround + 0.33);
    const Images lit = render(false), shaded = render(true);
    const glm::ivec2 p = pixelOf(deck);
    ASSERT_EQ(lit.label(p), objectLabel(0));
    ASSERT_EQ(shaded.label(p), objectLabel(0));
    EXPECT_GT(luminance(lit.rgb(p)), 3.0f * luminance(shaded.rgb(p)))
        << "lit " << luminance(lit.rgb(p)) << " vs shadowed " << luminance(shaded.rgb(p));
    // The plate is seen from below at the top of the image, labelled as object 1.
    size_t plate = 0;
    for (uint32_t label : shaded.labels) plate += label == objectLabel(1);
    EXPECT_GT(plate, 100u);
    EXPECT_EQ(shaded.label({int(kWidth) / 2, 0}), objectLabel(1));
}

TEST_F(ObjectRenderTest, ObjectNormalsAreTheirFacesPlanesInCameraAxes) {
    const Images images = render(true);
    // World direction `w` in the camera's axes (x right, y down, z forward).
    auto inCamera = [&](glm::dvec3 w) { return glm::transpose(camera.worldFromCamera) * w; };
    // The chassis' right side faces the camera in the south: world -y. The plate is seen from below: world -z.
    const glm::ivec2 side = pixelOf({50.0, 50.0 - 0.22, kGround + 0.22});
    ASSERT_EQ(images.label(side), objectLabel(0));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(images.normal(side)[c], inCamera({0, -1, 0})[c], 1e-5) << c;
    size_t plate = 0;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const glm::ivec2 p(x, y);
            const glm::dvec3 n = images.normal(p);
            if (images.label(p) == gpu::kSemanticSky << gpu::kInstanceBits) {
                ASSERT_EQ(n, glm::dvec3(0.0)) << x << "," << y;
                continue;
            }
            ASSERT_NEAR(glm::length(n), 1.0, 1e-5) << x << "," << y;
            ASSERT_LT(glm::dot(n, inCamera(camera.ray(x + 0.5, y + 0.5))), 0.0)
                << "faces the camera at " << x << "," << y;
            if (images.label(p) != objectLabel(1)) continue;
            ++plate;
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(n[c], inCamera({0, 0, -1})[c], 1e-5) << x << "," << y;
        }
    EXPECT_GT(plate, 100u);
}

// Dense from above (issue 18): looking straight down from 8 m over the default meadow, the plants and the turf
// under them cover the image; where the vegetation is sparse, the ground stays bare soil. Turf is a shading layer
// of the ground's own triangles: the truth pass labels exactly the pixels the colour pass shades as turf.
#include "gpu_test.h"

#include "common/half_float.h"
#include "render/scene_gpu.h"
#include "render/scene_renderer.h"
#include "scene/scene_resources.h"

using namespace sward;
using sward::test::GpuTest;

namespace {

constexpr uint32_t kWidth = 160, kHeight = 120;

struct ClassShares {
    double vegetation = 0.0, turf = 0.0, ground = 0.0;
};

ClassShares classShares(const FrameImages& frame) {
    ClassShares s;
    for (uint32_t label : frame.labels) {
        const uint32_t c = label >> gpu::kInstanceBits;
        const bool plant = (c >= gpu::kSemanticVegetation && c < gpu::kSemanticObject) || c == gpu::kSemanticFelled ||
                           c == gpu::kSemanticCut;
        s.vegetation += plant;
        s.turf += c == gpu::kSemanticTurf;
        s.ground += c == gpu::kSemanticGround;
    }
    const double n = double(frame.labels.size());
    return {s.vegetation / n, s.turf / n, s.ground / n};
}

// examples/meadow.json seen straight down from 8 m above the ground at (245, 180), its densities scaled by `density`.
FrameImages topDown(Context& ctx, double density) {
    Scene scene = loadScene(SWARD_SOURCE_DIR "/examples/meadow.json");
    scene.vegetation.densityMultiplier = float(density);
    SceneResources resources = buildSceneResources(std::move(scene), true, 2);
    const double ground = resources.terrain.height(glm::vec2(245.0f, 180.0f));
    const Camera camera = Camera::lookAt({245.0, 180.0, ground + 8.0}, {245.0, 180.01, ground}, {0.0, 0.0, 1.0},
                                         resources.scene.camera.fovYDegrees, kWidth, kHeight);
    SceneGpu gpu = createSceneGpu(ctx, resources, 1, SimulationMode::None);
    return renderFrame(ctx, *gpu.renderer, camera);
}

} // namespace

TEST_F(GpuTest, TurfClosesTheDefaultMeadowSeenFromAboveAndLeavesSparseGroundBare) {
    const ClassShares dense = classShares(topDown(*ctx, 1.0));
    std::printf("top down from 8 m: vegetation %.1f %%, turf %.1f %%, bare ground %.1f %%\n", 100.0 * dense.vegetation,
                100.0 * dense.turf, 100.0 * dense.ground);
    EXPECT_GE(dense.vegetation + dense.turf, 0.85);
    EXPECT_GT(dense.vegetation, 0.25) << "the plants themselves are still most of what is seen";

    // A twentieth of the density: a few plants per m^2 on open soil, no turf.
    const ClassShares sparse = classShares(topDown(*ctx, 0.05));
    EXPECT_EQ(sparse.turf, 0.0);
    EXPECT_GT(sparse.ground, 0.8);
}

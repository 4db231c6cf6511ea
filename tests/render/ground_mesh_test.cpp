// The example glTF ground (tools/make-example-data.py: two nested nodes with rotation, non-uniform scale and
// translation, Y up, "meadow" and "rock" materials) as the GPU draws it: every plant stands on a drawn triangle
// within 1 mm, never on rock, never steeper than the scene's slope limit. The drawn triangles are searched here
// independently of Ground's own grid.
#include "render/ground_mesh.h"
#include "scene/scene.h"
#include "vegetation/placement.h"
#include "vegetation/records.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <numbers>

using namespace sward;

namespace {

const std::string kHills = std::string(SWARD_EXAMPLES_DIR) + "/hills/hills.json";

struct DrawnHit {
    double z;
    glm::vec4 albedo;
    double normalZ; // of the triangle, winding-independent
};

// Top-most drawn triangle over xy, by brute force over a coarse bucket grid of the drawn triangles.
class DrawnSurface {
public:
    explicit DrawnSurface(const GroundDrawMesh& mesh) : mesh_(mesh) {
        lo_ = glm::dvec2(1e30), hi_ = glm::dvec2(-1e30);
        for (const gpu::TerrainVertex& v : mesh.vertices) {
            lo_ = glm::min(lo_, glm::dvec2(v.positionHeight));
            hi_ = glm::max(hi_, glm::dvec2(v.positionHeight));
        }
        cell_ = glm::max((hi_ - lo_) / double(kCells), glm::dvec2(1e-6));
        buckets_.resize(kCells * kCells);
        for (uint32_t t = 0; t < mesh.indices.size() / 3; ++t) {
            glm::dvec2 a = corner(t, 0), b = corner(t, 1), c = corner(t, 2);
            glm::ivec2 c0 = bucket(glm::min(a, glm::min(b, c))), c1 = bucket(glm::max(a, glm::max(b, c)));
            for (int y = c0.y; y <= c1.y; ++y)
                for (int x = c0.x; x <= c1.x; ++x) buckets_[size_t(y) * kCells + size_t(x)].push_back(t);
        }
    }

    std::optional<DrawnHit> at(glm::dvec2 p) const {
        std::optional<DrawnHit> best;
        const glm::ivec2 b = bucket(p);
        for (uint32_t t : buckets_[size_t(b.y) * kCells + size_t(b.x)]) {
            const glm::dvec3 a = vertex(t, 0), v1 = vertex(t, 1), v2 = vertex(t, 2);
            const double area = (v1.x - a.x) * (v2.y - a.y) - (v1.y - a.y) * (v2.x - a.x);
            if (area == 0.0) continue;
            const double w0 = ((v1.x - p.x) * (v2.y - p.y) - (v1.y - p.y) * (v2.x - p.x)) / area;
            const double w1 = ((v2.x - p.x) * (a.y - p.y) - (v2.y - p.y) * (a.x - p.x)) / area;
            const double w2 = 1.0 - w0 - w1;
            if (w0 < -1e-7 || w1 < -1e-7 || w2 < -1e-7) continue;
            const double z = w0 * a.z + w1 * v1.z + w2 * v2.z;
            if (best && z <= best->z) continue;
            const glm::dvec3 n = glm::normalize(glm::cross(v1 - a, v2 - a));
            best = DrawnHit{z, mesh_.vertices[mesh_.indices[3 * t]].albedo, std::abs(n.z)};
        }
        return best;
    }

private:
    static constexpr int kCells = 64;
    glm::dvec3 vertex(uint32_t t, int k) const { return glm::dvec3(mesh_.vertices[mesh_.indices[3 * t + k]].positionHeight); }
    glm::dvec2 corner(uint32_t t, int k) const { return glm::dvec2(vertex(t, k)); }
    glm::ivec2 bucket(glm::dvec2 p) const {
        return glm::clamp(glm::ivec2(glm::floor((p - lo_) / cell_)), glm::ivec2(0), glm::ivec2(kCells - 1));
    }

    const GroundDrawMesh& mesh_;
    glm::dvec2 lo_, hi_, cell_;
    std::vector<std::vector<uint32_t>> buckets_;
};

// The rock material's base colour, read from the glTF file itself.
glm::vec3 rockColour() {
    nlohmann::json gltf;
    std::ifstream(std::string(SWARD_EXAMPLES_DIR) + "/hills/hills.gltf") >> gltf;
    for (const auto& m : gltf["materials"])
        if (m["name"] == "rock") {
            const auto& f = m["pbrMetallicRoughness"]["baseColorFactor"];
            return glm::vec3(f[0].get<float>(), f[1].get<float>(), f[2].get<float>());
        }
    ADD_FAILURE() << "no rock material";
    return glm::vec3(-1.0f);
}

} // namespace

TEST(GroundMesh, PlantsStandOnTheDrawnGltfGroundNeverOnRockOrSteepSlopes) {
    const Scene scene = loadScene(kHills);
    const Ground ground = buildTerrain(scene);
    const GroundDrawMesh drawn = groundDrawMesh(ground);
    const DrawnSurface surface(drawn);
    const glm::vec3 rock = rockColour();
    const double minNormalZ = std::cos(scene.terrain.selection.maxSlopeDegrees * std::numbers::pi / 180.0);

    const VegetationTile tile = buildVegetation(scene, ground, 2);
    uint64_t plants = 0;
    double worst = 0.0;
    for (const FieldVegetation& field : tile.fields)
        for (const gpu::PlantStatic& record : field.staticRecords) {
            const glm::vec3 p = decodePlantPosition(record, field.origin, field.positionStep);
            const std::optional<DrawnHit> hit = surface.at(glm::dvec2(p));
            ASSERT_TRUE(hit) << "plant at " << p.x << ", " << p.y << " is off the drawn ground";
            worst = std::max(worst, std::abs(double(p.z) - hit->z));
            ASSERT_NE(glm::vec3(hit->albedo), rock) << "plant on rock at " << p.x << ", " << p.y;
            ASSERT_GE(hit->normalZ, minNormalZ - 1e-6) << "plant on a slope beyond the limit";
            ++plants;
        }
    EXPECT_LT(worst, 1e-3) << "a plant root is off the drawn surface by " << worst << " m";
    EXPECT_GT(plants, 100000u);
}

TEST(GroundMesh, RockAndMeadowAreBothDrawnAndTheMeshIsWhereItsNodesPutIt) {
    const Scene scene = loadScene(kHills);
    const Ground ground = buildTerrain(scene);
    const GroundDrawMesh drawn = groundDrawMesh(ground);
    ASSERT_EQ(drawn.indices.size(), size_t(48 * 48 * 6)); // every triangle of both primitives
    const glm::vec3 rock = rockColour();
    size_t rockCorners = 0;
    for (const gpu::TerrainVertex& v : drawn.vertices) rockCorners += glm::vec3(v.albedo) == rock;
    EXPECT_GT(rockCorners, 0u);
    EXPECT_LT(rockCorners, drawn.vertices.size() / 4);

    // The mesh-frame height h(x, z) of tools/make-example-data.py (glTF y).
    auto height = [](double x, double z) {
        const double knoll = 9.0 * std::exp(-((x - 30.0) * (x - 30.0) + (z + 20.0) * (z + 20.0)) / (2 * 14.0 * 14.0));
        return 5.0 * std::sin(x / 23.0) * std::cos(z / 31.0) + 0.03 * x + knoll;
    };
    // The mesh-frame vertex (x, z) = (0, 0), through the child (15 degrees about
    // y, 2 m up) and the parent (20 degrees about y, x scaled 1.5, moved by (120, 0, -110)), then Y-up -> Z-up.
    // Rotations about y leave the origin in place, so it lands at glTF (120, 2 + h, -110) = sward (120, 110, 2 + h).
    const std::optional<SurfacePoint> centre = ground.surface({120.0f, 110.0f});
    ASSERT_TRUE(centre);
    EXPECT_NEAR(centre->height, 2.0 + height(0.0, 0.0), 1e-4);
    // A mesh-frame corner (80, h, 80): child rotation, then parent scale, rotation and translation.
    auto rotY = [](glm::dvec3 p, double degrees) {
        const double a = degrees * std::numbers::pi / 180.0;
        return glm::dvec3(std::cos(a) * p.x + std::sin(a) * p.z, p.y, -std::sin(a) * p.x + std::cos(a) * p.z);
    };
    glm::dvec3 q = rotY(glm::dvec3(80.0, height(80.0, 80.0), 80.0), 15.0) + glm::dvec3(0.0, 2.0, 0.0);
    q = rotY(q * glm::dvec3(1.5, 1.0, 1.0), 20.0) + glm::dvec3(120.0, 0.0, -110.0);
    const glm::dvec3 world(q.x, -q.z, q.y);
    bool found = false;
    for (const gpu::TerrainVertex& v : drawn.vertices)
        found = found || glm::length(glm::dvec3(v.positionHeight) - world) < 1e-3;
    EXPECT_TRUE(found) << "no drawn vertex at " << world.x << ", " << world.y << ", " << world.z;
}

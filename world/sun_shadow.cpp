#include "world/sun_shadow.h"

#include "common/error.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace sward {

double shadowCasterReach(double sunUp) {
    const double up = std::clamp(sunUp, 0.0, 1.0);
    const double across = std::sqrt(1.0 - up * up);
    return 3.0 + std::min(1.5 * across / std::max(up, 1e-6), 37.0);
}

namespace {

// Each shell ends at least this many times farther than the one before: a shell that extends its predecessor by
// less than half (say 30-32 m when shadow_distance is just short of where the far billboards start) would cost a
// cascade's draws for almost no finer texels, so fewer, wider shells are used instead.
constexpr double kMinShellRatio = 1.5;

// At most `count` shell ends from `first` geometrically up to `last`, each at least kMinShellRatio times the one
// before (just `last` when first >= last or count is 1).
std::vector<double> geometricEnds(uint32_t count, double first, double last) {
    while (count > 1 && first < last && std::pow(last / first, 1.0 / double(count - 1)) < kMinShellRatio) --count;
    if (first >= last || count <= 1) return {last};
    std::vector<double> ends(count);
    for (uint32_t k = 0; k < count; ++k) ends[k] = first * std::pow(last / first, double(k) / double(count - 1));
    ends.back() = last; // exact, whatever pow rounded to
    return ends;
}

} // namespace

std::vector<double> shadowSplits(const ShadowCascadeParams& params) {
    require(params.cascades >= 1 && params.firstDistance > 0.0, "shadow cascades: at least one, first distance > 0");
    if (params.cascades == 1) return {params.firstDistance};
    const double farSplit = params.farPlantsFrom - params.casterMargin - 1.0;
    if (params.cascades >= 2 && farSplit >= 1.0 && farSplit < params.lastDistance) {
        std::vector<double> ends = geometricEnds(params.cascades - 1, std::min(params.firstDistance, farSplit), farSplit);
        ends.push_back(params.lastDistance);
        return ends;
    }
    if (params.firstDistance >= params.lastDistance) return {params.firstDistance};
    return geometricEnds(params.cascades, params.firstDistance, params.lastDistance);
}

glm::uvec2 shadowMapExtent(const ShadowCascadeParams& params) {
    return {uint32_t(shadowSplits(params).size()) * params.mapSize, params.mapSize};
}

namespace {

// Cosine of the widest angle between the view axis and a ray through the image: one of the corners. From the
// intrinsics alone (camera axes), so it is the same number however the camera is turned.
double widestCosine(const Camera& camera) {
    double widest = 1.0;
    for (const double u : {0.0, double(camera.width)})
        for (const double v : {0.0, double(camera.height)}) {
            const glm::dvec3 ray((u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy, 1.0);
            widest = std::min(widest, 1.0 / glm::length(ray));
        }
    return widest;
}

// Radius and centre (along the view axis) of a sphere holding every point of the frustum at distances [a, b]
// from the camera. The farthest points from an axis point are the shell's corners (on the widest rays) and its
// ends on the axis: the centre balances the near and far corners, kept within the shell.
glm::dvec2 shellSphere(double a, double b, double cosWidest) {
    const double c = std::clamp((a + b) / (2.0 * cosWidest), 0.0, b);
    auto toCorner = [&](double r) { return std::sqrt(std::max(r * r + c * c - 2.0 * r * c * cosWidest, 0.0)); };
    return {std::max({toCorner(a), toCorner(b), std::abs(a - c), std::abs(b - c)}), c};
}

// Orthographic reversed-Z projection of the light-space box centred on `center` (light view axes), half-edge
// `radius` across, +-`reach` along the light.
glm::dmat4 orthoReversed(const glm::dvec3& center, double radius, double reach) {
    glm::dmat4 ortho(0.0);
    ortho[0][0] = 1.0 / radius;
    ortho[1][1] = 1.0 / radius;
    ortho[2][2] = 1.0 / (2.0 * reach); // view z in [-(c+reach), -(c-reach)] -> depth 1 .. 0 (reversed)
    ortho[3][0] = -center.x / radius;
    ortho[3][1] = -center.y / radius;
    ortho[3][2] = 0.5 - center.z / (2.0 * reach);
    ortho[3][3] = 1.0;
    return ortho;
}

} // namespace

std::vector<ShadowCascade> fitShadowCascades(const Camera& camera, const glm::dvec3& toSun,
                                             const ShadowCascadeParams& params) {
    require(params.mapSize >= 1, "shadow cascades: a map of at least one texel");
    const std::vector<double> ends = shadowSplits(params);
    const glm::dvec3 up = std::abs(toSun.z) > 0.99 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
    const glm::dmat4 lightView = glm::lookAt(glm::dvec3(0.0), -toSun, up); // rotation only
    const glm::dvec3 forward = camera.worldFromCamera[2];
    const double cosWidest = widestCosine(camera);
    std::vector<ShadowCascade> cascades(ends.size());
    for (size_t k = 0; k < ends.size(); ++k) {
        ShadowCascade& cascade = cascades[k];
        cascade.mapSize = params.mapSize;
        cascade.mapOffset = uint32_t(k) * params.mapSize;
        cascade.begin = k == 0 ? 0.0 : ends[k - 1];
        cascade.end = ends[k];
        const double previousBegin = k < 2 ? 0.0 : ends[k - 2];
        cascade.firstReceiver = k == 0 ? 0.0 : cascade.begin - params.blend * (cascade.begin - previousBegin);
        const glm::dvec2 sphere = shellSphere(cascade.firstReceiver, cascade.end, cosWidest);
        cascade.radius = sphere.x + params.casterMargin;
        glm::dvec3 center = glm::dvec3(lightView * glm::dvec4(camera.position + forward * sphere.y, 1.0));
        const double texel = 2.0 * cascade.radius / double(cascade.mapSize);
        center.x = std::floor(center.x / texel) * texel;
        center.y = std::floor(center.y / texel) * texel;
        // Depth: from above the highest ground (plus plants and objects) to below the lowest, along the light.
        const double reach = cascade.radius + params.heightRange + 50.0;
        cascade.viewProj = orthoReversed(center, cascade.radius, reach) * lightView;
        // 5 cm, or 1.5 texels where texels are larger: a texel's depth spans its slope across it (acne otherwise).
        cascade.depthBias = std::max(0.05, 1.5 * texel) / (2.0 * reach);
    }
    return cascades;
}

} // namespace sward

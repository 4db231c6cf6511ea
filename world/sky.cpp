#include "world/sky.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sward {

namespace {

// Perez's F(theta, gamma) per channel (Y, x, y). cos theta is kept above 0.01 so the horizon stays finite.
glm::dvec3 perez(const PreethamSky& sky, double cosTheta, double gamma) {
    const double c = std::max(cosTheta, 0.01), cosGamma = std::cos(gamma);
    glm::dvec3 f;
    for (int k = 0; k < 3; ++k) {
        const double a = sky.perez[0][k], b = sky.perez[1][k], cc = sky.perez[2][k], d = sky.perez[3][k],
                     e = sky.perez[4][k];
        f[k] = (1.0 + a * std::exp(b / c)) * (1.0 + cc * std::exp(d * gamma) + e * cosGamma * cosGamma);
    }
    return f;
}

// The zenith's chromaticity: Preetham's cubic in the sun's zenith angle, quadratic in the turbidity.
double zenithChromaticity(const double (&m)[3][4], double t, double theta) {
    const glm::dvec3 tt(t * t, t, 1.0);
    double value = 0.0;
    for (int row = 0; row < 3; ++row)
        value += tt[row] * (((m[row][0] * theta + m[row][1]) * theta + m[row][2]) * theta + m[row][3]);
    return value;
}

} // namespace

double daylightChromaticity(double x, double y) {
    return std::max(y, (-3.0 * x + 2.87) * x - 0.275);
}

PreethamSky preethamSky(const glm::dvec3& sunDirection, double turbidity, double luminanceScale) {
    PreethamSky sky;
    const double t = std::clamp(turbidity, 1.7, 10.0);
    sky.sunDirection = glm::normalize(glm::dvec3(sunDirection.x, sunDirection.y, std::max(sunDirection.z, 0.0)));
    if (!std::isfinite(sky.sunDirection.x)) sky.sunDirection = glm::dvec3(0.0, 1.0, 0.0);
    sky.perez = {glm::dvec3(0.1787 * t - 1.4630, -0.0193 * t - 0.2592, -0.0167 * t - 0.2608),
                 glm::dvec3(-0.3554 * t + 0.4275, -0.0665 * t + 0.0008, -0.0950 * t + 0.0092),
                 glm::dvec3(-0.0227 * t + 5.3251, -0.0004 * t + 0.2125, -0.0079 * t + 0.2102),
                 glm::dvec3(0.1206 * t - 2.5771, -0.0641 * t - 0.8989, -0.0441 * t - 1.6537),
                 glm::dvec3(-0.0670 * t + 0.3703, -0.0033 * t + 0.0452, -0.0109 * t + 0.0529)};
    const double thetaSun = std::acos(std::clamp(sky.sunDirection.z, 0.0, 1.0));
    const double chi = (4.0 / 9.0 - t / 120.0) * (std::numbers::pi - 2.0 * thetaSun);
    const double zenithY = std::max((4.0453 * t - 4.9710) * std::tan(chi) - 0.2155 * t + 2.4192, 0.05);
    static constexpr double kX[3][4] = {{0.00166, -0.00375, 0.00209, 0.0},
                                        {-0.02903, 0.06377, -0.03202, 0.00394},
                                        {0.11693, -0.21196, 0.06052, 0.25886}};
    static constexpr double kY[3][4] = {{0.00275, -0.00610, 0.00317, 0.0},
                                        {-0.04214, 0.08970, -0.04153, 0.00516},
                                        {0.15346, -0.26756, 0.06670, 0.26688}};
    const glm::dvec3 zenith(zenithY * luminanceScale, zenithChromaticity(kX, t, thetaSun),
                            zenithChromaticity(kY, t, thetaSun));
    sky.zenithOverF0 = zenith / perez(sky, 1.0, thetaSun);
    return sky;
}

glm::dvec3 xyYToLinearSrgb(const glm::dvec3& xyY) {
    const double y = std::max(xyY.y, 1e-6);
    const double X = xyY.x / y * xyY.z, Y = xyY.z, Z = (1.0 - xyY.x - xyY.y) / y * xyY.z;
    return glm::max(glm::dvec3(3.2406 * X - 1.5372 * Y - 0.4986 * Z, -0.9689 * X + 1.8758 * Y + 0.0415 * Z,
                               0.0557 * X - 0.2040 * Y + 1.0570 * Z),
                    glm::dvec3(0.0));
}

glm::dvec3 skyRadiance(const PreethamSky& sky, const glm::dvec3& dir) {
    const double cosGamma = std::clamp(glm::dot(dir, sky.sunDirection), -1.0, 1.0);
    const glm::dvec3 v = sky.zenithOverF0 * perez(sky, dir.z, std::acos(cosGamma));
    return xyYToLinearSrgb(glm::dvec3(v.y, daylightChromaticity(v.y, v.z), v.x)); // (Y, x, y) -> (x, y, Y)
}

glm::dvec3 skyAmbient(const PreethamSky& sky) {
    constexpr int kRings = 12, kSectors = 32;
    glm::dvec3 sum(0.0);
    double weight = 0.0;
    for (int i = 0; i < kRings; ++i) {
        const double theta = (i + 0.5) / kRings * 0.5 * std::numbers::pi;
        const double w = std::cos(theta) * std::sin(theta); // cos for the surface, sin for the solid angle
        for (int j = 0; j < kSectors; ++j) {
            const double phi = (j + 0.5) / kSectors * 2.0 * std::numbers::pi;
            const glm::dvec3 dir(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
            sum += w * skyRadiance(sky, dir);
            weight += w;
        }
    }
    return sum / weight;
}

} // namespace sward

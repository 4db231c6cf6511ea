// The physical sky (world/sky.h): Preetham's published figures, its shape (bluer and darker at the zenith than at the
// horizon, brightest around the sun) and the ambient light it gives.
#include "world/sky.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

using namespace sward;

namespace {

glm::dvec3 sunAt(double elevationDegrees, double azimuthDegrees = 140.0) {
    const double el = elevationDegrees * M_PI / 180.0, az = azimuthDegrees * M_PI / 180.0;
    return {std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)};
}

double luminance(const glm::dvec3& rgb) {
    return 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z;
}

} // namespace

// Preetham's zenith luminance (kcd/m^2) for T = 3 and a sun 40 degrees high: (4.0453 T - 4.9710) tan chi - 0.2155 T
// + 2.4192, chi = (4/9 - T/120)(pi - 2 theta_s), about 6.53; the zenith's luminance is the model's Y there.
TEST(Sky, ZenithLuminanceIsPreethamsFormula) {
    const PreethamSky sky = preethamSky(sunAt(40.0), 3.0, 1.0);
    const double thetaSun = 50.0 * M_PI / 180.0, chi = (4.0 / 9.0 - 3.0 / 120.0) * (M_PI - 2.0 * thetaSun);
    const double expected = (4.0453 * 3.0 - 4.9710) * std::tan(chi) - 0.2155 * 3.0 + 2.4192;
    EXPECT_NEAR(expected, 6.53, 0.01);
    const glm::dvec3 zenith = skyRadiance(sky, {0.0, 0.0, 1.0});
    EXPECT_NEAR(luminance(zenith), expected, 0.02 * expected);
}

TEST(Sky, TheZenithIsBlueAndTheHorizonBrighterAndPaler) {
    const glm::dvec3 sun = sunAt(38.0);
    const PreethamSky sky = preethamSky(sun, 3.0, 0.08);
    const glm::dvec3 zenith = skyRadiance(sky, {0.0, 0.0, 1.0});
    const glm::dvec3 side = skyRadiance(sky, {-sun.y, sun.x, 0.0}),
                     away = skyRadiance(sky, -glm::dvec3(sun.x, sun.y, 0.0));
    EXPECT_GT(zenith.b, 1.5 * zenith.r);
    EXPECT_GT(luminance(side), luminance(zenith));
    // No purple horizon (daylightChromaticity; without it green is 0.89 of red and blue's mean here): neutral.
    EXPECT_GE(side.g, 0.98 * 0.5 * (side.r + side.b));
    EXPECT_GE(away.g, 0.98 * 0.5 * (away.r + away.b));
}

TEST(Sky, BrightestTowardsTheSunAndBrightestAtLowTurbidityAwayFromIt) {
    const glm::dvec3 sun = sunAt(30.0);
    const PreethamSky sky = preethamSky(sun, 3.0, 1.0);
    const glm::dvec3 horizontal(sun.x, sun.y, 0.0);
    const double toward = luminance(skyRadiance(sky, glm::normalize(horizontal + glm::dvec3(0.0, 0.0, 0.3))));
    const double away = luminance(skyRadiance(sky, glm::normalize(-horizontal + glm::dvec3(0.0, 0.0, 0.3))));
    EXPECT_GT(toward, 2.0 * away);
    // A hazier sky is brighter overall (more scattering): its ambient light too.
    EXPECT_GT(luminance(skyAmbient(preethamSky(sun, 6.0, 1.0))), luminance(skyAmbient(sky)));
}

// The ambient light lies between the darkest and the brightest sky it averages, and a sun below the horizon is taken
// at the horizon (finite values, no NaN from the model's tan).
TEST(Sky, AmbientIsAnAverageAndALowSunStaysFinite) {
    const PreethamSky sky = preethamSky(sunAt(40.0), 3.0, 1.0);
    const double ambient = luminance(skyAmbient(sky));
    EXPECT_GT(ambient, luminance(skyRadiance(sky, {0.0, 0.0, 1.0})));
    EXPECT_LT(ambient, luminance(skyRadiance(sky, glm::normalize(sunAt(40.0) + glm::dvec3(0.0, 0.0, 0.01)))));
    for (double elevation : {-10.0, 0.0, 2.0, 89.9}) {
        const PreethamSky low = preethamSky(sunAt(elevation), 2.5, 1.0);
        const glm::dvec3 a = skyAmbient(low), h = skyRadiance(low, {1.0, 0.0, 0.0});
        for (int k = 0; k < 3; ++k) {
            EXPECT_TRUE(std::isfinite(a[k]) && a[k] > 0.0) << elevation;
            EXPECT_TRUE(std::isfinite(h[k]) && h[k] >= 0.0) << elevation;
        }
    }
}

// The same inputs give the same sky, bit for bit (the frame constants are reproducible).
TEST(Sky, Reproducible) {
    const PreethamSky a = preethamSky(sunAt(38.0), 3.0, 0.08), b = preethamSky(sunAt(38.0), 3.0, 0.08);
    const glm::dvec3 x = skyAmbient(a), y = skyAmbient(b);
    EXPECT_EQ(std::memcmp(&x, &y, sizeof x), 0);
}

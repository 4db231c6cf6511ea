#include "render/sky_constants.h"

#include "world/sky.h"

#include <numbers>

namespace sward {

namespace {

glm::vec4 rgb(const glm::dvec3& v) {
    return glm::vec4(glm::vec3(v), 0.0f);
}

double luminance(const glm::vec3& v) {
    return 0.2126 * v.x + 0.7152 * v.y + 0.0722 * v.z;
}

} // namespace

void writeSkyConstants(const Scene& scene, gpu::FrameConstants& c) {
    const SkyParams& sky = scene.sky;
    const glm::dvec3 sun(scene.sun.direction());
    glm::dvec2 toSun(sun.x, sun.y);
    toSun = glm::length(toSun) > 1e-6 ? glm::normalize(toSun) : glm::dvec2(0.0, 1.0);
    const glm::dvec3 toward(toSun, 0.0), side(-toSun.y, toSun.x, 0.0);
    c.sunHorizontal = glm::vec4(float(toSun.x), float(toSun.y), 0.0f, 0.0f);
    c.groundAmbient = glm::vec4(sky.groundAmbient, 0.0f);
    const float extinction = sky.visibility > 0.0 ? float(kKoschmiederContrast / sky.visibility) : 0.0f;
    if (sky.model == SkyParams::Model::Gradient) {
        c.skyParams = glm::vec4(gpu::kSkyGradient, extinction, 0.0f, 0.0f);
        c.skyZenith = glm::vec4(sky.zenith, 0.0f);
        c.skyHorizon = glm::vec4(sky.horizon, 0.0f);
        // The gradient's ambient as before the physical sky: the mean of its two colours.
        c.skyAmbient = glm::vec4(0.5f * (sky.zenith + sky.horizon), 0.0f);
        c.hazeToward = c.hazeSide = c.hazeAway = c.skyHorizon;
        return;
    }
    const double scale = std::numbers::pi * luminance(scene.sun.radiance) / kSunIlluminanceKlx;
    const PreethamSky model = preethamSky(sun, sky.turbidity, scale);
    c.skyParams = glm::vec4(gpu::kSkyPhysical, extinction, float(sky.clouds), 0.0f);
    for (size_t k = 0; k < model.perez.size(); ++k) c.skyPerez[k] = rgb(model.perez[k]);
    c.skyZenithOverF0 = rgb(model.zenithOverF0);
    c.skyZenith = rgb(skyRadiance(model, glm::dvec3(0.0, 0.0, 1.0)));
    c.skyHorizon = rgb(skyRadiance(model, side));
    c.skyAmbient = rgb(skyAmbient(model));
    c.hazeToward = rgb(skyRadiance(model, toward));
    c.hazeSide = c.skyHorizon;
    c.hazeAway = rgb(skyRadiance(model, -toward));
}

} // namespace sward

// The physically based sky (issue 47): Preetham, Shirley and Smits, "A Practical Analytic Model for Daylight"
// (SIGGRAPH 1999). The sky's luminance Y and chromaticity x, y along a direction follow Perez et al.'s all-weather
// formula F(theta, gamma) = (1 + A e^(B / cos theta)) (1 + C e^(D gamma) + E cos^2 gamma) (theta from the zenith,
// gamma from the sun), scaled to the zenith's value, each of the five coefficients linear in the turbidity T (2:
// very clear, 3: clear, 6: hazy). Pure maths, the same on every machine: the render layer uploads the coefficients
// (FrameConstants), shaders/shared/frame.glsl evaluates them per pixel, and the CPU evaluates the same formula here
// for the ambient light and the aerial perspective's colour.
#pragma once

#include <glm/glm.hpp>

#include <array>

namespace sward {

struct PreethamSky {
    // Perez coefficients A..E, each for (Y, x, y).
    std::array<glm::dvec3, 5> perez{};
    // The zenith's (Y, x, y) divided by F(0, theta_sun), so that value(dir) = zenithOverF0 * F(theta, gamma); Y in
    // the scene's radiance units (see preethamSky's `luminanceScale`).
    glm::dvec3 zenithOverF0{0.0};
    glm::dvec3 sunDirection{0.0, 0.0, 1.0}; // unit, z up; the model's sun is at least at the horizon
};

// The sky for a sun along unit `sunDirection` (z up; a sun below the horizon is taken at the horizon) and turbidity
// `turbidity` (clamped to [1.7, 10], where the fit holds). Luminance is in the model's kcd/m^2 times
// `luminanceScale`. Preconditions: sunDirection has unit length.
PreethamSky preethamSky(const glm::dvec3& sunDirection, double turbidity, double luminanceScale);

// Linear sRGB radiance of the sky along unit direction `dir` (z up; directions below the horizon are taken at it).
glm::dvec3 skyRadiance(const PreethamSky& sky, const glm::dvec3& dir);

// The sky's cosine-weighted mean radiance over the upper hemisphere seen by a surface facing straight up
// (its irradiance / pi): the ambient light of an up-facing surface. A fixed 12 x 32 midpoint rule.
glm::dvec3 skyAmbient(const PreethamSky& sky);

// Preetham's chromaticity falls below the CIE daylight locus y = -3 x^2 + 2.87 x - 0.275 towards the horizon (its
// known purple cast, R = B > G); y is raised onto the locus there, which leaves the blue sky above it as it is and
// makes the horizon the neutral white of a hazy one. frame.glsl's physicalSky does the same.
double daylightChromaticity(double x, double y);

// CIE xyY (Y: luminance) to linear sRGB (Rec. 709 primaries, D65).
glm::dvec3 xyYToLinearSrgb(const glm::dvec3& xyY);

} // namespace sward

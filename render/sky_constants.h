// The sky's and the atmosphere's frame constants: the physical sky's coefficients (world/sky.h) or the scene's
// gradient, the ambient light consistent with either, and the aerial perspective's haze (shaders/shared/atmosphere.glsl).
#pragma once

#include "scene/scene.h"
#include "shared/gpu_layout.h"

namespace sward {

// The sun's illuminance at normal incidence the physical sky is scaled against, in klx: the sky's luminance in the
// scene's units is Preetham's kcd/m^2 times pi * luminance(sun.radiance) / this (plant and ground shading light a
// surface with sunRadiance * cos, i.e. sunRadiance is the sun's irradiance / pi).
inline constexpr double kSunIlluminanceKlx = 100.0;

// Koschmieder: a dark object vanishes at the visibility V where its contrast falls to 2 %: extinction 3.912 / V.
inline constexpr double kKoschmiederContrast = 3.912;

// Fills c's sky fields (skyZenith, skyHorizon, groundAmbient, skyParams .. sunHorizontal) from the scene's sky and sun.
void writeSkyConstants(const Scene& scene, gpu::FrameConstants& c);

} // namespace sward

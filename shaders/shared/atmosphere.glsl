// Aerial perspective (issue 47): the air between the camera and a surface dims the surface's light and adds the
// light it scatters towards the camera, so distant ground and plants fade, desaturate and lose contrast into the
// horizon's colour, brighter towards the sun. Included by frame.glsl; the colour pass only (the truth passes draw
// no colour), the last step of the terrain, plant and object shaders.
#ifndef SWARD_ATMOSPHERE_GLSL
#define SWARD_ATMOSPHERE_GLSL

// The in-scattered light seen along horizontal direction `h` (any length): the horizon's radiance, from across the
// sun's azimuth to towards it by the square of the cosine between them (fits Preetham's circumsolar rise at the
// horizon within a few % for a sun at 20-60 degrees) and linearly to away from it.
vec3 hazeColour(vec2 h) {
    float len = length(h);
    float c = len > 0.0 ? dot(h, frame.sunHorizontal.xy) / len : 0.0;
    return c >= 0.0 ? mix(frame.hazeSide.rgb, frame.hazeToward.rgb, c * c)
                    : mix(frame.hazeSide.rgb, frame.hazeAway.rgb, -c);
}

// The haze between the camera and the surface at `world`: Koschmieder's uniform atmosphere, the transmittance
// exp(-extinction * distance) (extinction 3.912 / visibility: 2 % contrast left at the visibility). rgb: the light
// it scatters towards the camera, a: the transmittance (applyHaze). Plants take it per vertex and interpolate it:
// across a card or a blade the distance changes by a few per cent at most, where the exponential is linear to well
// under one level of 255, and on lavapipe each fragment would pay an exp, two square roots and both sides of
// hazeColour's branch (the meadow's main pass 1.07x).
vec4 hazeAt(vec3 world) {
    float extinction = frame.skyParams.y;
    if (extinction <= 0.0) return vec4(0.0, 0.0, 0.0, 1.0);
    vec3 toSurface = world - frame.cameraPosition.xyz;
    float transmittance = exp(-extinction * length(toSurface));
    return vec4(hazeColour(toSurface.xy) * (1.0 - transmittance), transmittance);
}

// `color` of a surface as the camera sees it through `haze` (hazeAt).
vec3 applyHaze(vec3 color, vec4 haze) { return color * haze.a + haze.rgb; }

// `color` of the surface at `world` as the camera sees it through the haze, computed here (ground and objects).
vec3 aerialPerspective(vec3 color, vec3 world) { return applyHaze(color, hazeAt(world)); }

#endif

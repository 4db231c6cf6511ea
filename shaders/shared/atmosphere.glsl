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

// `color` of the surface at `world` as the camera sees it through the haze: Koschmieder's uniform atmosphere, the
// transmittance exp(-extinction * distance) (extinction 3.912 / visibility: 2 % contrast left at the visibility).
vec3 aerialPerspective(vec3 color, vec3 world) {
    float extinction = frame.skyParams.y;
    if (extinction <= 0.0) return color;
    vec3 toSurface = world - frame.cameraPosition.xyz;
    float transmittance = exp(-extinction * length(toSurface));
    return mix(hazeColour(toSurface.xy), color, transmittance);
}

#endif

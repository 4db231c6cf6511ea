// The vegetation's cover map under the ground (vegetation/cover_map.h): what terrain.frag shades as turf and far
// cover, and what truth.frag labels as turf. Both passes evaluate it at the pixel centre's world position with the
// same sampler, so a pixel shaded as turf is labelled turf. Needs frame.glsl first.
#ifndef SWARD_GROUND_COVER_GLSL
#define SWARD_GROUND_COVER_GLSL

#include "shared/hash_noise.glsl"

layout(set = 0, binding = kBindingCoverMap) uniform sampler2D coverMap;
layout(push_constant) uniform Push { TerrainTileConstants tile; };

// `world` in the cover's tile (u east, v north, 0..1 across the tile).
vec2 coverUv(vec3 world) { return (world.xy - tile.coverRect.xy) * tile.coverRect.z; }

// Whether uv lies on the tile or within one pixel's footprint beyond its edge. With MSAA a pixel its tile's triangles
// cover only in part is shaded at its centre, which may lie just beyond the tile: such a pixel of a world's tile border
// read no cover, a faint line along every border; it reads the tile's edge instead. (The truth pass, 1x, shades only
// centres its triangles cover.)
bool inCoverTile(vec2 uv) {
    vec2 margin = fwidth(uv);
    return tile.coverRect.z != 0.0 && all(greaterThanEqual(uv, -margin)) && all(lessThanEqual(uv, 1.0 + margin));
}

// rgb linear albedo of the cover, a S (m^2 of plant side area per m^2); zero off the tile or without vegetation.
vec4 groundCover(vec2 uv) {
    if (!inCoverTile(uv)) return vec4(0.0);
    uv = clamp(uv, vec2(0.0), vec2(1.0));
    return texture(coverMap, vec2(uv.x, 1.0 - uv.y)); // the texture's v runs north to south, as the grass map's
}

// How much of the ground at `world` is turf: turfFraction of the cover's S, read at a point displaced by noise of
// 3 m down to 15 cm (at most about half a metre), so the border between meadow and bare ground wanders and frays
// instead of following the grass map's texels in a straight step. Inside a closed meadow or bare field the
// displaced point has the same S, and nothing changes. The colour and the truth pass both call this.
float turfAt(vec3 world) {
    vec2 warp = 0.8 * vec2(valueNoise(world.xy, 3.0, 81u), valueNoise(world.xy, 3.0, 84u)) +
                0.25 * vec2(valueNoise(world.xy, 0.7, 82u), valueNoise(world.xy, 0.7, 85u)) +
                0.06 * vec2(valueNoise(world.xy, 0.15, 83u), valueNoise(world.xy, 0.15, 86u));
    vec2 uv = coverUv(world + vec3(warp - 0.555, 0.0));
    // Within half a metre of a tile's border the displaced point may lie in the neighbouring tile, whose cover this
    // draw does not bind: it reads this tile's edge instead, so a world's tiles meet without a line of bare ground
    // (and of `ground` labels) along every border.
    if (inCoverTile(coverUv(world))) uv = clamp(uv, vec2(0.0), vec2(1.0));
    return turfFraction(groundCover(uv).a);
}

#endif

// The vegetation's cover map under the ground (vegetation/cover_map.h): what terrain.frag shades as turf and far
// cover, and what truth.frag labels as turf. Both passes evaluate it at the pixel centre's world position with the
// same sampler, so a pixel shaded as turf is labelled turf. Needs frame.glsl first.
#ifndef SWARD_GROUND_COVER_GLSL
#define SWARD_GROUND_COVER_GLSL

layout(set = 0, binding = kBindingCoverMap) uniform sampler2D coverMap;
layout(push_constant) uniform Push { TerrainTileConstants tile; };

// `world` in the cover's tile (u east, v north, 0..1 across the tile).
vec2 coverUv(vec3 world) { return (world.xy - tile.coverRect.xy) * tile.coverRect.z; }

bool inCoverTile(vec2 uv) {
    return tile.coverRect.z != 0.0 && all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
}

// rgb linear albedo of the cover, a S (m^2 of plant side area per m^2); zero outside the tile or without vegetation.
vec4 groundCover(vec2 uv) {
    if (!inCoverTile(uv)) return vec4(0.0);
    return texture(coverMap, vec2(uv.x, 1.0 - uv.y)); // the texture's v runs north to south, as the grass map's
}

#endif

// Ground tracks (render/track_renderer.h): is a point of the coarse ground inside a block drawn as a rut patch?
// The patched blocks sit in an open-addressing table (a power of two of entries (x, y, instance, 0), linear probing
// from trackBlockHash, empty entries kTrackEmptyKey), at most half full, so a lookup ends at an empty entry.
#ifndef SWARD_GROUND_TRACKS_GLSL
#define SWARD_GROUND_TRACKS_GLSL

layout(set = 0, binding = kBindingTrackTable, std430) readonly buffer TrackTable { ivec4 trackEntries[]; };

bool inTrackPatch(vec2 xy) {
    ivec2 block = ivec2(floor(xy / (kTrackCell * float(kTrackBlockCells))));
    uint mask = uint(trackEntries.length()) - 1u;
    uint slot = trackBlockHash(block.x, block.y) & mask;
    for (uint probe = 0u; probe <= mask; ++probe) {
        ivec4 entry = trackEntries[slot];
        if (entry.x == block.x && entry.y == block.y) return true;
        if (entry.x == kTrackEmptyKey) return false;
        slot = (slot + 1u) & mask;
    }
    return false;
}

#endif

// A check of an OpenEXR file's headers before OpenEXR reads them. OpenEXR allocates from what a header states —
// an attribute's size, the line-offset table for the data window, a table entry per tile, line buffers for the
// channels — before it reads the data, so a 300-byte file can make it allocate gigabytes. Internal to io/.
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace sward {

// The largest uncompressed chunk (the lines OpenEXR decodes at once, all channels) sward lets OpenEXR allocate.
inline constexpr uint64_t kMaxExrChunkBytes = uint64_t(256) << 20;
// More channels than any image sward reads could use (it reads R,G,B,A or one channel).
inline constexpr uint32_t kMaxExrChannels = 64;

// Walks every header of `bytes` (name, type, size, value; an empty name ends a header, an empty header ends a
// multi-part file's headers) and throws sward::Error naming `path` unless: each attribute fits the bytes that
// follow; OpenEXR's fixed-layout types (box2i, tiledesc, chlist, ...) have exactly their layout's size, so that
// this walk and OpenEXR's read the same values; the data window is 1..kMaxImageEdge pixels per edge; the
// channels are at most kMaxExrChannels and a chunk at most kMaxExrChunkBytes; a tiled image's offset table
// (8 bytes a tile) fits in the file.
void requireSafeExrHeaders(const std::string& path, std::span<const char> bytes);

} // namespace sward

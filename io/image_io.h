// Reading image files (grass maps, heightfields, ground truth): 8/16-bit PNG and float OpenEXR, decoded to float
// samples. Writing is io/image_files.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace sward {

// Decoded image. Row 0 is the top row of the file; samples are interleaved, channels per pixel.
struct ImageData {
    uint32_t width = 0, height = 0;
    uint32_t channels = 0;      // 1 grey, 2 grey+alpha, 3 RGB, 4 RGBA
    uint32_t bitDepth = 0;      // 8 or 16 for PNG, 32 for EXR
    std::vector<float> samples; // PNG: normalised to [0, 1]; EXR: the stored values, unchanged
    std::string source;         // the file name, for error messages

    float at(uint32_t x, uint32_t y, uint32_t c) const { return samples[(size_t(y) * width + x) * channels + c]; }
};

// Largest accepted edge, in pixels: guards against corrupt headers asking for gigabytes.
inline constexpr uint32_t kMaxImageEdge = 32768;
// Largest decoded image, priced from the file's header before a pixel is allocated: width x height x channels x
// (4 bytes of the float sample + the decoder's own 1 or 2 bytes a sample for PNG). 2 GiB holds an 8192x8192 RGBA
// 8-bit PNG (1.25 GiB) or a 16384x16384 one-channel float EXR (1 GiB); a 1 MB PNG of 16384x16384 RGB (4 GiB, and
// the grass map's consumers copy it again) is refused in microseconds instead of taking 10 GB and minutes.
inline constexpr uint64_t kMaxDecodedImageBytes = uint64_t(2) << 30;

// Loads a .png (8 or 16 bits per sample; palette images count as 8-bit RGB(A)) or .exr (any pixel type, read as
// float; channels R,G,B[,A], or a single channel such as Y or Z). Throws sward::Error naming the file and the
// problem for a missing file, an unknown extension, a bit depth below 8, or a corrupt file.
ImageData loadImage(const std::string& path);
// One named channel of an .exr file (e.g. the instance image's 'tile' in a world), as one-channel float samples.
// Throws sward::Error naming the file and the channel when the file has no such channel.
ImageData loadExrChannel(const std::string& path, const std::string& channel);
// The channel names of an .exr file, in the file's (alphabetical) order.
std::vector<std::string> exrChannelNames(const std::string& path);
// Largest image file read, in bytes (far above a 32768-pixel EXR's compressed size).
inline constexpr uint64_t kMaxImageFileBytes = uint64_t(4) << 30;
// The bytes of a regular image file of at most kMaxImageFileBytes; throws sward::Error naming the file otherwise.
std::vector<char> readImageFileBytes(const std::string& path);
// A path's extension after its last dot, lower-cased ("" when there is none): "a/B.PNG" -> "png".
std::string lowerExtension(const std::string& path);
// Decodes a PNG held in memory with the same checks; `path` names it in errors (e.g. "'ground.glb' image 2").
// `maxEdge` (at most kMaxImageEdge) is checked against the header before anything is decoded.
ImageData decodePng(const std::string& path, const std::vector<char>& bytes, uint32_t maxEdge = kMaxImageEdge);
// The same PNG as 8-bit RGBA (grey g -> g, g, g, 255; grey + alpha -> g, g, g, a; RGB -> r, g, b, 255; 16-bit samples
// rounded to 8 bits), with the same checks, sets width and height: 8-bit images never pass through floats.
std::vector<unsigned char> decodePngRgba8(const std::string& path, const std::vector<char>& bytes, uint32_t maxEdge,
                                          uint32_t& width, uint32_t& height);

} // namespace sward

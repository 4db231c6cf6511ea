// Writing image files: OpenEXR (HDR colour, float depth and ids) and PNG (previews, 8-bit masks). Reading is
// io/image_io.h.
//
// Every writer encodes the whole file in memory and writes it with writeBytesAtomically (common/atomic_file.h),
// so an interrupted or failed run never leaves a half-written file under a final name. Errors (a full disk
// included) throw one sward::Error naming the file.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sward {

// Colour: single-part scanline EXR with half-float channels R, G, B, A (linear, scene-referred).
// `rgbaHalf` holds width*height*4 IEEE half bit patterns, row-major, top row first (as read back).
void writeExrRgbaHalf(const std::string& path, uint32_t width, uint32_t height, std::span<const uint16_t> rgbaHalf);

// Depth: single-part scanline EXR with one float32 channel named "Y" (what OpenCV reads as a one-channel
// float image) and, by default, a copy named "Z" for tools that expect a Z depth channel. OpenCV 4.6
// returns zeros for a file whose only channel is "Z", hence "Y" is always present.
void writeExrDepth(const std::string& path, uint32_t width, uint32_t height, std::span<const float> depth,
                   bool withZCopy = true);

// Generic float EXR with named channels (channels.size() planes of width*height floats each).
void writeExrFloatChannels(const std::string& path, uint32_t width, uint32_t height,
                           const std::vector<std::string>& names, const std::vector<std::span<const float>>& planes);

// Float samples (interleaved, `channels` per pixel, top row first) as float32 EXR channels: 1 channel is
// written as "Y", 3 or 4 as R, G, B[, A]. The inverse of loadImage (image_io.h) for EXR files.
void writeExr(const std::string& path, uint32_t width, uint32_t height, uint32_t channels,
              const std::vector<float>& samples);

// PNG of 8-bit (writePng8) or 16-bit (writePng16) samples, 1, 3 or 4 channels a pixel in the file's order (grey,
// RGB, RGBA), top row first, written atomically. Every PNG sward writes goes through one encoder: libpng with
// OpenCV's settings (zlib's fastest level with its run-length strategy; the files are the bytes OpenCV wrote when
// sward encoded through it, and a build without OpenCV writes them too), which on sward's previews and masks is
// about 4 times faster than stb's encoder and gives files a fifth to a third smaller.
void writePng8(const std::string& path, uint32_t width, uint32_t height, uint32_t channels,
               std::span<const uint8_t> pixels);
void writePng16(const std::string& path, uint32_t width, uint32_t height, uint32_t channels,
                std::span<const uint16_t> samples);

// The preview's tone curve on one linear RGB colour: exposure, then Narkowicz's ACES filmic curve fit on the
// luminance with the colour scaled by the same ratio (hue and saturation kept), and a channel that would pass 1
// desaturating towards grey at the same luminance. Result in [0, 1], linear. sward-view's present.frag is a copy.
std::array<float, 3> toneMap(std::array<float, 3> linear, float exposure);

// Linear HDR half RGBA -> 8-bit sRGB RGB preview: toneMap, then sRGB encoding.
std::vector<uint8_t> tonemapPreview(std::span<const uint16_t> rgbaHalf, uint32_t width, uint32_t height,
                                    float exposure = 0.5f);

// Creates `dir` (and parents) and checks a file can be written there; throws a clear error otherwise.
void ensureWritableDirectory(const std::string& dir);

} // namespace sward

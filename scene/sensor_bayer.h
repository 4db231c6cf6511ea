// A single-chip colour sensor (issue 48's ISP): a Bayer colour filter array and the ISP's demosaicing.
//
// Real robot cameras have one photosite per pixel behind a red, green or blue filter in a 2 x 2 tile repeated over
// the chip; the ISP interpolates the two colours each pixel lacks, with zipper and false colour at fine,
// high-contrast detail (grass blades). The key camera.sensor.bayer names the tile in reading order: "RGGB" is R at
// pixel (0, 0), G at (1, 0) and (0, 1), B at (1, 1) (the top-left pixel is the image's first). Absent or null: the
// three-channel sensor of before, every image bit for bit.
//
// Physics order in SensorModel::apply (scene/sensor_model.h): the lens (optics), distortion, vignetting and exposure
// act on the light first; then each photosite keeps only its filter's channel, and sensorReadout
// (scene/sensor_exposure.h) gives it its own shot and read noise (one gaussian per pixel, keyed by the photosite's
// channel), gain, white balance, black level and clip; then demosaic() interpolates. White balance is thus a gain on
// the mosaic before demosaicing, as a real ISP applies it (a per-channel gain on each photosite is the same thing).
//
// Demosaicing ("demosaic"): both methods are linear filters on the mosaic, + and * by multiples of 1/8 only, in
// double precision, so bitwise the same everywhere; a photosite's own channel is never changed (the raw mosaic is
// each pixel's own channel of the output). Borders reflect the mosaic about the edge pixel (OpenCV's
// BORDER_REFLECT_101), which keeps the pattern's parity. Outputs are not clamped (like the noise, an interpolated value
// may fall below 0 or above the white level next to an edge).
//   "bilinear" (default): the mean of the nearest photosites of the missing colour (2 or 4 in the 3 x 3 window),
//                         as OpenCV's cv::demosaicing(COLOR_Bayer*2BGR).
//   "malvar": Malvar, He and Cutler 2004, "High-quality linear interpolation for demosaicing of Bayer-patterned
//             colour images": bilinear corrected by the photosite's own channel's Laplacian (5 x 5 kernels), less
//             false colour and zipper at edges.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace sward {

class JsonReader;
struct SensorParams;

enum class BayerPattern : uint8_t { None, Rggb, Bggr, Grbg, Gbrg };
enum class Demosaic : uint8_t { Bilinear, Malvar };

struct ColourFilterArray {
    BayerPattern pattern = BayerPattern::None; // None: a three-channel sensor (no mosaic, nothing demosaiced)
    Demosaic demosaic = Demosaic::Bilinear;

    bool enabled() const { return pattern != BayerPattern::None; }
};

// The channel (0 R, 1 G, 2 B) of the photosite at pixel (x, y). Precondition: pattern != None.
uint32_t bayerChannel(BayerPattern pattern, uint32_t x, uint32_t y);
// "RGGB", "BGGR", "GRBG", "GBRG" (the key's values); "none" for None.
const char* bayerPatternName(BayerPattern pattern);

// The mosaic of a linear RGBA float image: each pixel's own channel, width*height values, top row first.
std::vector<float> bayerMosaic(BayerPattern pattern, uint32_t width, uint32_t height, std::span<const float> rgba);
// Replaces the two channels each pixel's photosite lacks by the chosen interpolation of the mosaic (each pixel's own
// channel of `rgba`, which stays as it is; alpha untouched). Precondition: cfa enabled, rgba width*height*4.
void demosaic(const ColourFilterArray& cfa, uint32_t width, uint32_t height, std::span<float> rgba);

// Reads "bayer" (null, "RGGB", "BGGR", "GRBG", "GBRG") and "demosaic" ("bilinear", "malvar"; only with a pattern)
// into `params.cfa`; errors name the key ('camera.sensor.bayer'). A pattern needs an enabled sensor.
void parseColourFilterArray(JsonReader& reader, SensorParams& params);
// Adds "bayer" and "demosaic" to a sensor's JSON with a pattern (absent without: records as before).
void colourFilterArrayToJson(const ColourFilterArray& cfa, nlohmann::json& json);

} // namespace sward

// The camera's digital output (issue 48): the ADC's digital numbers (DN) of the sensor's linear signal, written by
// the dataset writer beside the linear EXR as raw/NNNNNN.png (raw_right/ for stereo; docs/dataset-format.md).
//
// Per pixel and colour channel, from the sensor model's float output s (scene/sensor_model.h: after the lens, the
// noise, the gain, white balance, the black level and the ADC's clip; before the image is rounded to half):
//   DN = floor(clamp(s / white_level, 0, 1) * (2^bit_depth - 1) + 0.5)      (round half up; NaN gives 0)
//   white_level = black_level + full_well / electrons_per_unit   with full_well set (the ADC's clip)
//               = 1                                               otherwise (1 unit of linear radiance is full scale)
// in double precision with * / + and floor only: the same bits on every machine. The DN are linear (no gamma, no
// tone curve): the camera's raw output; the preview stays the tone-mapped image. A three-channel sensor (no
// camera.sensor.bayer) gives an RGB raw image; a Bayer sensor (scene/sensor_bayer.h) gives the single-channel mosaic,
// each pixel its photosite's own channel's DN (the filter pattern is recorded with the sensor in frames.jsonl), taken
// before demosaicing: the ISP's interpolation is in the EXR and the preview only. The pedestal stays in the DN (a
// black pixel reads black_level / white_level of full scale), as a real camera's raw does. White balance is in the DN
// (sensorReadout applies it per photosite, before the ADC).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace sward {

class JsonReader;
struct SensorParams;

// The bit depths the key accepts; 0 = no digital output.
inline constexpr uint32_t kRawBitDepths[] = {8, 10, 12, 14, 16};

// The signal that reads full scale (white_level above). Precondition: params valid (parseSensor).
double rawWhiteLevel(const SensorParams& params);
// The DN of one channel's signal `signal` with `whiteLevel` at `bitDepth` bits (one of kRawBitDepths).
uint16_t rawDigitalNumber(double signal, double whiteLevel, uint32_t bitDepth);
// The DN of a linear RGBA float image `width` pixels wide, top row first: R, G, B per pixel (alpha dropped;
// rgba.size() / 4 * 3 values), or with a Bayer pattern one per pixel, its photosite's own channel (the mosaic;
// rgba.size() / 4 values). Precondition: params.bitDepth is one of kRawBitDepths.
std::vector<uint16_t> rawDigitalImage(const SensorParams& params, std::span<const float> rgba, uint32_t width);

// Reads "bit_depth" (0 or one of kRawBitDepths; errors name 'camera.sensor.bit_depth') into `params.bitDepth`.
// A sensor with "enabled": false and a bit depth is refused: it has no signal to digitise.
void parseRawBitDepth(JsonReader& reader, SensorParams& params);

} // namespace sward

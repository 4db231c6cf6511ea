// Rolling shutter (camera.sensor.readout_s and readout_bands; docs/scene-format.md).
//
// A rolling-shutter sensor reads its rows one after the other over the readout time: row r (top row 0) of an image
// of H rows is read at
//   t_r = t + readout_s * ((r + 0.5) / H - 0.5),
// so the frame's time t is the middle of the readout (the middle row's time, as a shutter's is the exposure's
// middle). sward renders each row at its own time: the rows are grouped in `bands` bands of consecutive rows
// (readout_bands; default, and at most, H: every row its own band, exact), each band is rendered whole with the rig,
// the objects and the wind at the band's time (the time of its middle: the mean of its rows' times) and only its rows
// are kept. Fewer bands are cheaper, and the rows of a band share its time. The colour AND every truth image (depth,
// disparity, labels, normals, flow, motion_blur) of a row are those of its band's render: the truth is per row. With
// a shutter too, each band's colour is the exposure (render/motion_blur.h) centred on the band's time. Both cameras
// of a synchronised stereo rig read row r at the same time; an unsynchronised rig's right camera
// (camera.sensor.stereo_offset_s, render/sequence_frame.h) reads it at readoutRowTime(t + offset, ...), in a readout
// of its own whose right view is kept. The interaction ticks once per frame: every band
// sees the state of the frame's own tick, like a shutter's sub-frames. Cost: about `bands` colour and truth renders
// per frame (each a full-image render: no scissor yet).
#pragma once

#include "dataset/frame_images.h"
#include "render/motion_blur.h"
#include "scene/camera_rig.h"

#include <nlohmann/json_fwd.hpp>
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace sward {

// Consecutive rows [firstRow, endRow) read at `time`.
struct ReadoutBand {
    uint32_t firstRow = 0, endRow = 0;
    double time = 0.0;
};

// The readout time of row `row` of `height` rows for a frame at `time`.
double readoutRowTime(double time, double readoutSeconds, uint32_t row, uint32_t height);

// The `bands` bands of an image of `height` rows (bands 0 or more than height: one per row), band b holding rows
// [b H / B, (b + 1) H / B), each at the mean of its rows' times (a one-row band: exactly readoutRowTime).
std::vector<ReadoutBand> readoutBands(double time, double readoutSeconds, uint32_t height, uint32_t bands);

// Copies rows [firstRow, endRow) of every image `from` has into `to` (sized like `from` where still empty).
void copyRows(const FrameImages& from, FrameImages& to, uint32_t firstRow, uint32_t endRow);

// The frame's images read out band by band: first the colour of every band (`colourAt(time, first)`: the prologue,
// the frame's tick, goes with the first), then the truth (`truthAt(time, first)`: a truth-only render, whose next
// tick for the flow, if any, goes with the first), each band's rows copied out. Colour first: no truth pass's tick
// can reach a later band's colour.
FrameImages composeReadout(std::span<const ReadoutBand> bands, uint32_t width, uint32_t height,
                           const std::function<ExposureColour(double, bool)>& colourAt,
                           const std::function<FrameImages(double, bool)>& truthAt);

// Rolling-shutter colour of one band: the exposure of `exposureSamples` sub-frames (0: no shutter, an instant)
// centred on `time`, of the rig `rigAt`, with `prologue` (the frame's tick) before the first render.
ExposureColour renderBandColour(SceneRenderer& renderer, OffscreenFrame& target,
                                const std::function<RigCameras(double)>& rigAt, bool stereo, double time,
                                double shutterSeconds, uint32_t exposureSamples, double timeOffset, uint32_t frameIndex,
                                const std::function<void(VkCommandBuffer)>& prologue);

// frames.jsonl's "readout" of `frame` (null without a rolling shutter): readout_s, bands and, for the first and the
// last row, their time and the rig's poses then.
nlohmann::json readoutRecord(const SceneResources& r, const SensorParams& sensor, uint32_t width, uint32_t height,
                             uint32_t frame);

} // namespace sward

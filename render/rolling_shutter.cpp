#include "render/rolling_shutter.h"

#include "common/error.h"
#include "dataset/frame_record.h"
#include "render/scene_renderer.h"
#include "render/sequence_frame.h"

#include <nlohmann/json.hpp>

#include <algorithm>

namespace sward {

double readoutRowTime(double time, double readoutSeconds, uint32_t row, uint32_t height) {
    return time + readoutSeconds * ((double(row) + 0.5) / double(height) - 0.5);
}

std::vector<ReadoutBand> readoutBands(double time, double readoutSeconds, uint32_t height, uint32_t bands) {
    require(height >= 1, "readoutBands: an image has at least one row");
    if (bands == 0 || bands > height) bands = height;
    std::vector<ReadoutBand> out(bands);
    for (uint32_t b = 0; b < bands; ++b) {
        ReadoutBand& band = out[b];
        band.firstRow = uint32_t(uint64_t(b) * height / bands);
        band.endRow = uint32_t(uint64_t(b + 1) * height / bands);
        // (first + end) / 2H is (r + 0.5) / H for a single row r: the same real number, so the same rounding.
        band.time = time + readoutSeconds * ((double(band.firstRow) + double(band.endRow)) / (2.0 * height) - 0.5);
    }
    return out;
}

namespace {

// Rows [first, end) of an image of `rows` rows with any number of values per row.
template <class T>
void copyImageRows(const std::vector<T>& from, std::vector<T>& to, uint32_t rows, uint32_t first, uint32_t end) {
    if (from.empty()) return;
    if (to.empty()) to.resize(from.size());
    require(to.size() == from.size() && from.size() % rows == 0, "copyRows: the images' sizes differ");
    const size_t perRow = from.size() / rows;
    std::copy(from.begin() + first * perRow, from.begin() + end * perRow, to.begin() + first * perRow);
}

} // namespace

void copyRows(const FrameImages& from, FrameImages& to, uint32_t firstRow, uint32_t endRow) {
    const uint32_t h = from.height;
    require(firstRow <= endRow && endRow <= h, "copyRows: rows outside the image");
    to.width = from.width, to.height = from.height;
    copyImageRows(from.rgbaHalf, to.rgbaHalf, h, firstRow, endRow);
    copyImageRows(from.depth, to.depth, h, firstRow, endRow);
    copyImageRows(from.labels, to.labels, h, firstRow, endRow);
    copyImageRows(from.tiles, to.tiles, h, firstRow, endRow);
    copyImageRows(from.normals, to.normals, h, firstRow, endRow);
    copyImageRows(from.rightRgbaHalf, to.rightRgbaHalf, h, firstRow, endRow);
    copyImageRows(from.rightDepth, to.rightDepth, h, firstRow, endRow);
    copyImageRows(from.rightLabels, to.rightLabels, h, firstRow, endRow);
    copyImageRows(from.rightNormals, to.rightNormals, h, firstRow, endRow);
    copyImageRows(from.flowForward, to.flowForward, h, firstRow, endRow);
    copyImageRows(from.flowBackward, to.flowBackward, h, firstRow, endRow);
    copyImageRows(from.rightFlowForward, to.rightFlowForward, h, firstRow, endRow);
    copyImageRows(from.rightFlowBackward, to.rightFlowBackward, h, firstRow, endRow);
    copyImageRows(from.motionBlur, to.motionBlur, h, firstRow, endRow);
}

FrameImages composeReadout(std::span<const ReadoutBand> bands, uint32_t width, uint32_t height,
                           const std::function<ExposureColour(double, bool)>& colourAt,
                           const std::function<FrameImages(double, bool)>& truthAt) {
    FrameImages out{.width = width, .height = height};
    for (size_t b = 0; b < bands.size(); ++b) {
        ExposureColour colour = colourAt(bands[b].time, b == 0);
        FrameImages band{.width = width, .height = height};
        band.rgbaHalf = std::move(colour.left);
        band.rightRgbaHalf = std::move(colour.right);
        copyRows(band, out, bands[b].firstRow, bands[b].endRow);
    }
    for (size_t b = 0; b < bands.size(); ++b) {
        FrameImages truth = truthAt(bands[b].time, b == 0);
        truth.rgbaHalf.clear(), truth.rightRgbaHalf.clear(); // the colour is the colour pass's above
        copyRows(truth, out, bands[b].firstRow, bands[b].endRow);
    }
    return out;
}

ExposureColour renderBandColour(SceneRenderer& renderer, OffscreenFrame& target,
                                const std::function<RigCameras(double)>& rigAt, bool stereo, double time,
                                double shutterSeconds, uint32_t exposureSamples, double timeOffset, uint32_t frameIndex,
                                const std::function<void(VkCommandBuffer)>& prologue) {
    if (exposureSamples > 0)
        return renderExposure(renderer, target, rigAt, stereo, exposureTimes(time, shutterSeconds, exposureSamples),
                              timeOffset, frameIndex, prologue);
    const RigCameras rig = rigAt(time);
    ExposureColour colour;
    target.renderColour(renderer, rig.left, timeOffset + time, frameIndex, prologue, stereo ? &rig.right : nullptr,
                        colour.left, &colour.right);
    if (!stereo) colour.right.clear();
    return colour;
}

nlohmann::json readoutRecord(const SceneResources& r, const SensorParams& sensor, uint32_t width, uint32_t height,
                             uint32_t frame) {
    if (!sensor.enabled || sensor.readoutSeconds <= 0.0) return nullptr;
    const double time = double(frame) * r.scene.sequence.timeStep;
    const std::vector<ReadoutBand> bands = readoutBands(time, sensor.readoutSeconds, height, sensor.readoutBands);
    // An unsynchronised rig's right camera reads its rows around its own time (render/sequence_frame.h).
    const double offset = sensor.stereoOffsetSeconds;
    const std::vector<ReadoutBand> rightBands =
        offset != 0.0 ? readoutBands(time + offset, sensor.readoutSeconds, height, sensor.readoutBands) : bands;
    auto row = [&](const ReadoutBand& band, const ReadoutBand& rightBand) {
        const RigCameras rig = sequenceRigAt(r, width, height, band.time);
        nlohmann::json json = {{"time", band.time}, {"left_pose", cameraPoseJson(rig.left)}};
        if (offset != 0.0) {
            json["right_time"] = rightBand.time;
            json["right_pose"] = cameraPoseJson(sequenceRigAt(r, width, height, rightBand.time).right);
        } else if (r.scene.camera.rig.stereo()) {
            json["right_pose"] = cameraPoseJson(rig.right);
        }
        return json;
    };
    return {{"readout_s", sensor.readoutSeconds},
            {"bands", bands.size()},
            {"first_row", row(bands.front(), rightBands.front())},
            {"last_row", row(bands.back(), rightBands.back())}};
}

} // namespace sward

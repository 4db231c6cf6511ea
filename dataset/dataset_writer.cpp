#include "dataset/dataset_writer.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/parse_number.h"
#include "dataset/naming.h"
#include "io/disparity_files.h"
#include "io/image_files.h"
#include "io/sha256.h"
#include "scene/camera_rig.h"
#include "shared/gpu_layout.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace sward {

namespace fs = std::filesystem;

void shardRange(uint32_t first, uint32_t end, uint32_t index, uint32_t count, uint32_t& shardFirst,
                uint32_t& shardEnd) {
    const uint64_t n = end - first;
    shardFirst = first + uint32_t(n * index / count);
    shardEnd = first + uint32_t(n * (index + 1) / count);
}

void parseShard(const std::string& text, uint32_t& index, uint32_t& count) {
    // At most one shard per frame: more shards than frames a scene can hold is a typo, not a job array.
    const std::string what = "bad shard '" + text + "'";
    const auto [i, n] = splitPair(text, '/', what, "I/N with 0 <= I < N, e.g. 0/4");
    count = uint32_t(parseUnsigned(n, 1, kFrameLimit, what + ": shard count N"));
    index = uint32_t(parseUnsigned(i, 0, count - 1, what + ": shard index I"));
}

DatasetWriter::DatasetWriter(std::string root, bool stereo) : root_(std::move(root)), stereo_(stereo) {}

std::vector<std::string> DatasetWriter::directories() const {
    std::vector<std::string> dirs = {kLeftFolder, kDepthFolder, kSemanticFolder, kInstanceFolder, kPreviewFolder};
    if (stereo_) dirs.insert(dirs.end(), {kRightFolder, kDisparityFolder, kPreviewRightFolder});
    return dirs;
}

void DatasetWriter::prepare() const {
    ensureWritableDirectory(root_);
    for (const std::string& dir : directories()) {
        ensureWritableDirectory(root_ + "/" + dir);
        for (const fs::directory_entry& entry : fs::directory_iterator(root_ + "/" + dir))
            if (entry.path().extension() == ".tmp") fs::remove(entry.path());
    }
    for (const fs::directory_entry& entry : fs::directory_iterator(root_))
        if (entry.path().extension() == ".tmp") fs::remove(entry.path());
}

std::vector<std::string> DatasetWriter::frameFiles(uint32_t frame) const {
    std::vector<std::string> files = {frameFile(kLeftFolder, frame, ".exr"), frameFile(kDepthFolder, frame, ".exr"),
                                      frameFile(kSemanticFolder, frame, ".png"),
                                      frameFile(kInstanceFolder, frame, ".exr"),
                                      frameFile(kPreviewFolder, frame, ".png")};
    if (stereo_)
        files.insert(files.end(),
                     {frameFile(kRightFolder, frame, ".exr"), frameFile(kDisparityFolder, frame, ".exr"),
                      frameFile(kDisparityFolder, frame, ".pfm"), frameFile(kDisparityFolder, frame, ".png"),
                      frameFile(kPreviewRightFolder, frame, ".png")});
    return files;
}

std::vector<std::string> DatasetWriter::datasetFiles() const {
    std::vector<std::string> files = {kFrameLogFile};
    if (stereo_) files.push_back(kCalibFile);
    return files;
}

bool DatasetWriter::frameComplete(uint32_t frame) const {
    for (const std::string& file : frameFiles(frame))
        if (!fs::is_regular_file(root_ + "/" + file)) return false;
    return true;
}

void DatasetWriter::writeFrame(uint32_t frame, const FrameImages& images, const Camera& left, double baseline) const {
    const uint32_t w = images.width, h = images.height;
    const size_t pixels = size_t(w) * h;
    auto path = [&](const char* folder, const char* extension) {
        return root_ + "/" + frameFile(folder, frame, extension);
    };

    std::vector<uint8_t> semantic(pixels);
    std::vector<float> instance(pixels);
    for (size_t i = 0; i < pixels; ++i) {
        semantic[i] = uint8_t(images.labels[i] >> gpu::kInstanceBits);
        instance[i] = float(images.labels[i] & ((1u << gpu::kInstanceBits) - 1u)); // exact: ids < 2^24
    }
    writeExrRgbaHalf(path(kLeftFolder, ".exr"), w, h, images.rgbaHalf);
    writeExrDepth(path(kDepthFolder, ".exr"), w, h, images.depth);
    writePng8(path(kSemanticFolder, ".png"), w, h, 1, semantic);
    writeExrFloatChannels(path(kInstanceFolder, ".exr"), w, h, {"Y"}, {instance});
    writePng8(path(kPreviewFolder, ".png"), w, h, 3, tonemapPreview(images.rgbaHalf, w, h));
    if (!stereo_) return;

    std::vector<float> disparity(pixels);
    for (size_t i = 0; i < pixels; ++i) disparity[i] = disparityOf(left.fx, baseline, images.depth[i]);
    writeExrRgbaHalf(path(kRightFolder, ".exr"), w, h, images.rightRgbaHalf);
    writeExrFloatChannels(path(kDisparityFolder, ".exr"), w, h, {"Y"}, {disparity});
    writePfm(path(kDisparityFolder, ".pfm"), w, h, disparity);
    writeKittiPng(path(kDisparityFolder, ".png"), w, h, disparity);
    writePng8(path(kPreviewRightFolder, ".png"), w, h, 3, tonemapPreview(images.rightRgbaHalf, w, h));
}

void DatasetWriter::writeCalib(const Camera& left, double baseline, double minDepth) const {
    // OpenCV / Middlebury put pixel centres at whole coordinates, sward (camera.h) at +0.5: shift by half a pixel.
    StereoCalib calib;
    calib.cam0 = {left.fx, 0, left.cx - 0.5, 0, left.fy, left.cy - 0.5, 0, 0, 1};
    calib.cam1 = calib.cam0;
    calib.doffs = 0.0;
    calib.baselineMm = baseline * 1000.0;
    calib.width = left.width;
    calib.height = left.height;
    const double maxDisparity = left.fx * baseline / minDepth;
    calib.ndisp = std::max(16u, uint32_t(std::ceil(maxDisparity / 16.0)) * 16u);
    calib.vmin = 0.0;
    calib.vmax = maxDisparity;
    writeMiddleburyCalib(root_ + "/" + kCalibFile, calib);
}

void DatasetWriter::writeFrameLog(const std::vector<nlohmann::json>& records) const {
    std::string text;
    for (const nlohmann::json& record : records) text += record.dump() + "\n";
    writeTextAtomically(root_ + "/" + kFrameLogFile, text);
}

void DatasetWriter::writeManifest(const std::string& name, nlohmann::json info,
                                  const std::vector<std::string>& files) const {
    nlohmann::json hashes = nlohmann::json::object();
    for (const std::string& file : files) hashes[file] = sha256File(root_ + "/" + file);
    info["files"] = std::move(hashes);
    writeTextAtomically(root_ + "/" + name, info.dump(2) + "\n");
}

} // namespace sward

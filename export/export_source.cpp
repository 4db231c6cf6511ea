#include "export/export_source.h"

#include "common/error.h"
#include "common/input_file.h"
#include "dataset/fingerprint.h"
#include "dataset/naming.h"
#include "io/disparity_files.h"
#include "io/image_io.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string_view>

namespace sward {

namespace fs = std::filesystem;

namespace {

glm::dmat4 poseOf(const nlohmann::json& rows) {
    glm::dmat4 m(1.0);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) m[c][r] = rows.at(r).at(c).get<double>();
    return m;
}

// Every record of frames.jsonl, by frame number; also sets the camera from the first record.
std::vector<ExportFrame> readFrameLog(const std::string& dir, ExportCamera& camera, bool& stereo) {
    const std::string path = dir + "/" + kFrameLogFile;
    std::istringstream file(readInputFile(path, "frame log (not a complete sward dataset?)"));
    std::vector<ExportFrame> frames;
    uint32_t lineNumber = 0;
    for (std::string line; std::getline(file, line);) {
        ++lineNumber;
        try {
            const nlohmann::json record = nlohmann::json::parse(line);
            // sward-render lists every frame of the sequence once, in order from 0: anything else (a duplicate gives
            // one image two poses, a negative or skipped number drops a frame) is a damaged file, never exported.
            const nlohmann::json& number = record.at("frame");
            require(number.is_number_unsigned() && number.get<uint64_t>() == frames.size(),
                    path + " line " + std::to_string(lineNumber) + ": frame " + number.dump() + ", expected " +
                        std::to_string(frames.size()) +
                        " (frames.jsonl lists frames 0, 1, 2, ... in order, each once)");
            ExportFrame frame{.frame = number.get<uint32_t>(), .leftPose = poseOf(record.at("left_pose"))};
            stereo = record.contains("right_pose");
            if (stereo) frame.rightPose = poseOf(record.at("right_pose"));
            if (frames.empty()) {
                const nlohmann::json& k = record.at("intrinsics");
                camera = {.fx = k.at("fx"),
                          .fy = k.at("fy"),
                          .cx = k.at("cx"),
                          .cy = k.at("cy"),
                          .width = k.at("width"),
                          .height = k.at("height"),
                          .baseline = stereo ? record.at("baseline").get<double>() : 0.0};
                if (record.contains("sensor") && record["sensor"].value("enabled", true)) {
                    const nlohmann::json& s = record["sensor"];
                    camera.distortion = {s.at("k1"), s.at("k2"), s.at("p1"), s.at("p2"), s.at("k3")};
                }
            }
            frames.push_back(frame);
        } catch (const nlohmann::json::exception& e) {
            throw Error(path + " line " + std::to_string(lineNumber) + ": not a sward frame record (" + e.what() + ")");
        }
    }
    require(!frames.empty(), path + " holds no frame records");
    return frames;
}

void requireFrameSize(const ExportDataset& dataset, const std::string& path, uint32_t width, uint32_t height) {
    require(width == dataset.camera.width && height == dataset.camera.height,
            path + ": " + std::to_string(width) + "x" + std::to_string(height) + ", expected " +
                std::to_string(dataset.camera.width) + "x" + std::to_string(dataset.camera.height) + " (frames.jsonl)");
}

// A decoded image of the dataset with the frame's size and `channels` channels.
ImageData readFrameImage(const ExportDataset& dataset, const char* folder, uint32_t frame, const char* extension,
                         uint32_t channels) {
    const std::string path = dataset.dir + "/" + frameFile(folder, frame, extension);
    ImageData image = loadImage(path);
    requireFrameSize(dataset, path, image.width, image.height);
    require(image.channels == channels,
            path + ": " + std::to_string(image.channels) + " channel(s), expected " + std::to_string(channels));
    return image;
}

} // namespace

ExportDataset openExportDataset(const std::string& dir, std::optional<std::pair<uint32_t, uint32_t>> range) {
    std::error_code ec;
    require(fs::is_directory(dir, ec), "'" + dir + "' is not a folder (expected a dataset written by sward-render)");
    require(fs::exists(dir + "/" + kDatasetFile, ec),
            "'" + dir + "' is not a sward dataset: it has no " + kDatasetFile + " (written by sward-render)");
    readDatasetFingerprint(dir + "/" + kDatasetFile); // throws for a description sward did not write
    ExportDataset dataset{.dir = dir};
    for (const ExportFrame& frame : readFrameLog(dir, dataset.camera, dataset.stereo)) {
        if (range && (frame.frame < range->first || frame.frame >= range->second)) continue;
        if (fs::is_regular_file(dir + "/" + frameFile(kDepthFolder, frame.frame, ".exr"), ec))
            dataset.frames.push_back(frame);
    }
    require(!dataset.frames.empty(),
            "'" + dir + "' has no rendered frame" +
                (range ? " in " + std::to_string(range->first) + ":" + std::to_string(range->second) : std::string()));
    return dataset;
}

FrameTruth readFrameTruth(const ExportDataset& dataset, uint32_t frame) {
    const ImageData depth = readFrameImage(dataset, kDepthFolder, frame, ".exr", 1);
    const ImageData semantic = readFrameImage(dataset, kSemanticFolder, frame, ".png", 1);
    const ImageData instance = readFrameImage(dataset, kInstanceFolder, frame, ".exr", 1);
    const ImageData preview = readFrameImage(dataset, kPreviewFolder, frame, ".png", 3);
    FrameTruth truth{.width = depth.width, .height = depth.height, .depth = depth.samples};
    const size_t pixels = size_t(truth.width) * truth.height;
    truth.semantic.resize(pixels);
    truth.instance.resize(pixels);
    truth.rgb.resize(pixels * 3);
    // PNG samples come normalised to [0, 1]: 8-bit values are exact multiples of 1/255.
    for (size_t i = 0; i < pixels; ++i) {
        truth.semantic[i] = uint8_t(std::lround(semantic.samples[i] * 255.0f));
        // Ids are integers below 2^24, exact in float32; anything else is a damaged file (and no cast of it).
        const float id = instance.samples[i];
        require(id >= 0.0f && id < 16777216.0f && id == std::floor(id),
                instance.source + ": pixel " + std::to_string(i % truth.width) + ", " +
                    std::to_string(i / truth.width) + " holds " + std::to_string(id) + ", not an instance id");
        truth.instance[i] = uint32_t(id);
    }
    for (size_t i = 0; i < pixels * 3; ++i) truth.rgb[i] = uint8_t(std::lround(preview.samples[i] * 255.0f));
    std::error_code ec;
    if (fs::is_regular_file(dataset.dir + "/" + frameFile(kNormalFolder, frame, ".exr"), ec))
        truth.normal = readFrameImage(dataset, kNormalFolder, frame, ".exr", 3).samples;
    return truth;
}

void requireUndistorted(const ExportDataset& dataset, const char* layout) {
    require(!dataset.camera.distorted(),
            "'" + dataset.dir +
                "' was rendered with lens distortion (camera.sensor k1, k2, k3, p1, p2): its images no "
                "longer line up with the undistorted ground truth the " +
                layout +
                " layout pairs them with; render "
                "without distortion, or export colmap / nerfstudio, which carry the coefficients");
}

std::vector<float> readFrameDisparity(const ExportDataset& dataset, uint32_t frame) {
    const std::string path = dataset.dir + "/" + frameFile(kDisparityFolder, frame, ".pfm");
    DisparityMap map = readPfm(path);
    requireFrameSize(dataset, path, map.width, map.height);
    return std::move(map.values);
}

std::vector<uint8_t> readOcclusionMask(const ExportDataset& dataset, uint32_t frame) {
    const ImageData mask = readFrameImage(dataset, kOcclusionFolder, frame, ".png", 1);
    std::vector<uint8_t> values(mask.samples.size());
    for (size_t i = 0; i < values.size(); ++i) values[i] = uint8_t(std::lround(mask.samples[i] * 255.0f));
    return values;
}

std::vector<char> readFrameFileBytes(const ExportDataset& dataset, const char* folder, uint32_t frame,
                                     const char* extension) {
    const std::string path = dataset.dir + "/" + frameFile(folder, frame, extension);
    const bool pfm = std::string_view(extension) == ".pfm";
    uint32_t width = 0, height = 0;
    if (pfm) {
        const DisparityMap map = readPfm(path);
        width = map.width, height = map.height;
    } else {
        const ImageData image = loadImage(path);
        width = image.width, height = image.height;
    }
    requireFrameSize(dataset, path, width, height);
    return readImageFileBytes(path);
}

std::vector<char> readCalibBytes(const ExportDataset& dataset) {
    const std::string path = dataset.dir + "/" + kCalibFile;
    const StereoCalib calib = readMiddleburyCalib(path);
    requireFrameSize(dataset, path, calib.width, calib.height);
    return readImageFileBytes(path);
}

} // namespace sward

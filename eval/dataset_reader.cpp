#include "eval/dataset_reader.h"

#include "common/error.h"
#include "common/input_file.h"
#include "dataset/naming.h"
#include "io/image_io.h"

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <filesystem>
#include <sstream>

namespace fs = std::filesystem;

namespace sward {

namespace {

bool isFile(const std::string& path) {
    std::error_code ec;
    return fs::is_regular_file(path, ec);
}

} // namespace

std::vector<uint32_t> listFrameFiles(const std::string& dir, const char* folder,
                                     const std::vector<std::string>& extensions, const std::string& what) {
    const std::string path = dir + "/" + folder;
    std::error_code ec;
    require(fs::is_directory(path, ec), dir + " has no " + what + " '" + path + "'");
    std::vector<uint32_t> frames;
    for (const auto& entry : fs::directory_iterator(path, ec)) {
        const std::optional<uint32_t> frame = frameNumber(entry.path().stem().string());
        const std::string ext = entry.path().extension().string();
        if (frame && std::find(extensions.begin(), extensions.end(), ext) != extensions.end()) frames.push_back(*frame);
    }
    require(!ec, "cannot list '" + path + "': " + ec.message());
    std::sort(frames.begin(), frames.end());
    frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
    return frames;
}

std::vector<uint32_t> listDatasetFrames(const std::string& dir, const char* folder) {
    return listFrameFiles(dir, folder, {".pfm", ".exr", ".png"},
                          std::string(folder) == kDisparityFolder ? "ground-truth folder" : "folder");
}

std::map<uint32_t, cv::Matx44d> readLeftPoses(const std::string& dir) {
    const std::string path = dir + "/" + kFrameLogFile;
    std::istringstream file(readInputFile(path, "frame log (not a complete sward dataset?)"));
    std::map<uint32_t, cv::Matx44d> poses;
    uint32_t lineNumber = 0;
    for (std::string line; std::getline(file, line);) {
        ++lineNumber;
        try {
            const nlohmann::json record = nlohmann::json::parse(line);
            cv::Matx44d pose;
            for (int r = 0; r < 4; ++r)
                for (int c = 0; c < 4; ++c) pose(r, c) = record.at("left_pose").at(r).at(c).get<double>();
            poses[record.at("frame").get<uint32_t>()] = pose;
        } catch (const nlohmann::json::exception& e) {
            throw Error(path + " line " + std::to_string(lineNumber) + ": not a sward frame record (" + e.what() + ")");
        }
    }
    return poses;
}

std::vector<float> readDepth(const std::string& dir, uint32_t frame, uint32_t width, uint32_t height) {
    const std::string path = dir + "/" + frameFile(kDepthFolder, frame, ".exr");
    require(isFile(path), "missing depth image '" + path + "'");
    ImageData image = loadExrChannel(path, "Y");
    require(image.width == width && image.height == height && image.channels == 1,
            path + ": expected a one-channel float depth image of " + std::to_string(width) + "x" +
                std::to_string(height));
    return std::move(image.samples);
}

DisparityMap readGroundTruth(const std::string& dir, uint32_t frame) {
    const std::string base = dir + "/" + frameFile(kDisparityFolder, frame, "");
    if (isFile(base + ".pfm")) return readPfm(base + ".pfm");
    if (isFile(base + ".exr")) {
        ImageData image = loadImage(base + ".exr");
        require(image.channels == 1, base + ".exr: expected a one-channel (Y) disparity image");
        DisparityMap map{image.width, image.height, std::move(image.samples)};
        for (float& v : map.values)
            if (!isValidDisparity(v)) v = 0.0f;
        return map;
    }
    if (isFile(base + ".png")) return readKittiPng(base + ".png");
    throw Error("missing ground truth for frame " + frameName(frame) + ": no " + base + ".pfm, .exr or .png");
}

cv::Mat readPreview(const std::string& dir, const char* folder, uint32_t frame, bool gray) {
    const std::string path = dir + "/" + frameFile(folder, frame, ".png");
    require(isFile(path), "missing image '" + path + "'");
    cv::Mat image = cv::imread(path, gray ? cv::IMREAD_GRAYSCALE : cv::IMREAD_COLOR);
    require(!image.empty() && image.depth() == CV_8U, "cannot decode image '" + path + "' as 8-bit PNG");
    return image;
}

namespace {

// An 8-bit one-channel image of the frame (`what` names it in errors: "semantic image", "occlusion mask").
cv::Mat readByteImage(const std::string& dir, const char* folder, uint32_t frame, uint32_t width, uint32_t height,
                      const std::string& what) {
    const std::string path = dir + "/" + frameFile(folder, frame, ".png");
    require(isFile(path), "missing " + what + " '" + path + "'");
    cv::Mat image = cv::imread(path, cv::IMREAD_UNCHANGED);
    require(!image.empty() && image.type() == CV_8UC1 && image.cols == int(width) && image.rows == int(height),
            path + ": expected an 8-bit one-channel " + what + " of " + std::to_string(width) + "x" +
                std::to_string(height));
    return image;
}

} // namespace

cv::Mat readSemantic(const std::string& dir, uint32_t frame, uint32_t width, uint32_t height) {
    return readByteImage(dir, kSemanticFolder, frame, width, height, "semantic image");
}

cv::Mat readOcclusion(const std::string& dir, uint32_t frame, uint32_t width, uint32_t height) {
    return readByteImage(dir, kOcclusionFolder, frame, width, height, "occlusion mask");
}

FlowField readFlowTruth(const std::string& dir, uint32_t frame) {
    const std::string base = dir + "/" + frameFile(kFlowForwardFolder, frame, "");
    if (isFile(base + ".flo")) return readFlo(base + ".flo");
    if (isFile(base + ".png")) return readKittiFlowPng(base + ".png");
    throw Error("missing flow ground truth for frame " + frameName(frame) + ": no " + base + ".flo or .png");
}

cv::Mat readFlowMask(const std::string& dir, uint32_t frame, uint32_t width, uint32_t height) {
    return readByteImage(dir, kFlowForwardMaskFolder, frame, width, height, "flow mask");
}

FlowField readFlowEstimate(const std::string& flowDir, uint32_t frame, uint32_t width, uint32_t height) {
    const std::string base = flowDir + "/" + frameName(frame);
    const std::string path = isFile(base + ".flo") ? base + ".flo" : base + ".png";
    require(isFile(path),
            "no flow for frame " + frameName(frame) + ": neither '" + base + ".flo' nor '" + path + "' exists");
    FlowField flow = readFlow(path);
    require(flow.width == width && flow.height == height, path + " is " + std::to_string(flow.width) + "x" +
                                                              std::to_string(flow.height) + ", the ground truth " +
                                                              std::to_string(width) + "x" + std::to_string(height));
    return flow;
}

std::vector<float> readEstimate(const std::string& disparitiesDir, uint32_t frame, uint32_t width, uint32_t height) {
    const std::string name = frameName(frame);
    std::string path = disparitiesDir + "/" + name + ".pfm";
    if (!isFile(path)) path = disparitiesDir + "/" + name + ".png";
    require(isFile(path), "no estimate for frame " + name + ": neither '" + disparitiesDir + "/" + name +
                              ".pfm' nor '" + path + "' exists");
    DisparityMap map = readDisparity(path);
    require(map.width == width && map.height == height, path + " is " + std::to_string(map.width) + "x" +
                                                            std::to_string(map.height) + ", the ground truth " +
                                                            std::to_string(width) + "x" + std::to_string(height));
    return std::move(map.values);
}

} // namespace sward

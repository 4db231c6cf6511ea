// Reading what the evaluations need from a sward dataset (names: dataset/naming.h): the frame lists, ground-truth
// disparity and optical flow, the preview views the matchers run on, class images, masks and depth, and another
// method's estimates. Every function throws sward::Error naming the file and the problem.
#pragma once

#include "dataset/naming.h"
#include "io/disparity_files.h"
#include "io/flow_files.h"

#include <opencv2/core.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace sward {

// Frame numbers of the files <dir>/<folder>/NNNNNN<extension> (6 digits, extension one of `extensions`, e.g.
// ".pfm"), sorted; `what` names the folder in the error when it does not exist ("ground-truth folder").
std::vector<uint32_t> listFrameFiles(const std::string& dir, const char* folder,
                                     const std::vector<std::string>& extensions, const std::string& what);

// Frame numbers of a dataset: every 6-digit NNNNNN.{pfm,exr,png} in <dir>/<folder> (default: the ground-truth
// disparity), sorted.
std::vector<uint32_t> listDatasetFrames(const std::string& dir, const char* folder = kDisparityFolder);

// The left camera's pose of every record of frames.jsonl (4x4 camera-to-world, OpenCV axes), by frame number.
std::map<uint32_t, cv::Matx44d> readLeftPoses(const std::string& dir);

// depth/NNNNNN.exr (planar depth in metres, +inf for sky) of width x height, row-major.
std::vector<float> readDepth(const std::string& dir, uint32_t frame, uint32_t width, uint32_t height);

// Ground-truth disparity of one frame: disparity/NNNNNN.pfm, else .exr, else the KITTI .png (lossy).
DisparityMap readGroundTruth(const std::string& dir, uint32_t frame);

// The 8-bit preview of one view (`folder`: kPreviewFolder or kPreviewRightFolder), grey or BGR.
cv::Mat readPreview(const std::string& dir, const char* folder, uint32_t frame, bool gray);

// semantic/NNNNNN.png, which must be a one-channel 8-bit image of width x height.
cv::Mat readSemantic(const std::string& dir, uint32_t frame, uint32_t width, uint32_t height);

// occlusion/NNNNNN.png (dataset/occlusion.h: 255 = visible in both views), a one-channel 8-bit image of
// width x height.
cv::Mat readOcclusion(const std::string& dir, uint32_t frame, uint32_t width, uint32_t height);

// Ground-truth forward flow of one frame (to frame + 1): flow_forward/NNNNNN.flo, else the KITTI .png (lossy).
FlowField readFlowTruth(const std::string& dir, uint32_t frame);

// flow_forward_mask/NNNNNN.png (255 = visible in both frames), one-channel 8-bit of width x height.
cv::Mat readFlowMask(const std::string& dir, uint32_t frame, uint32_t width, uint32_t height);

// Another method's forward flow <flowDir>/NNNNNN.flo, else the KITTI .png, of width x height.
FlowField readFlowEstimate(const std::string& flowDir, uint32_t frame, uint32_t width, uint32_t height);

// Another matcher's estimate <disparitiesDir>/NNNNNN.pfm, else the KITTI .png, of width x height.
std::vector<float> readEstimate(const std::string& disparitiesDir, uint32_t frame, uint32_t width, uint32_t height);

} // namespace sward

// Dataset naming: the one table of a dataset's folder and file names and of its semantic classes, used by the
// writer (sward-render) and by the evaluation (sward-eval), so both always agree (docs/dataset-format.md).
#pragma once

#include "scene/range_sensors.h"

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace sward {

// Folders of a dataset, one per kind of per-frame file.
inline constexpr const char* kLeftFolder = "left";                  // left colour, half RGBA EXR
inline constexpr const char* kRightFolder = "right";                // right colour (stereo)
inline constexpr const char* kDepthFolder = "depth";                // planar depth EXR
inline constexpr const char* kDisparityFolder = "disparity";        // disparity EXR, PFM, KITTI PNG (stereo)
inline constexpr const char* kSemanticFolder = "semantic";          // uint8 class PNG
inline constexpr const char* kInstanceFolder = "instance";          // float instance id EXR
inline constexpr const char* kNormalFolder = "normal";              // camera-frame surface normal, float RGB EXR
inline constexpr const char* kPreviewFolder = "preview";            // tonemapped left PNG
inline constexpr const char* kPreviewRightFolder = "preview_right"; // tonemapped right PNG (stereo)
inline constexpr const char* kDepthRightFolder = "depth_right";         // the right view's planar depth EXR (stereo)
inline constexpr const char* kDisparityRightFolder = "disparity_right"; // right disparity EXR, PFM (stereo)
inline constexpr const char* kOcclusionFolder = "occlusion";            // left pixels visible in the right view (stereo)
inline constexpr const char* kOcclusionRightFolder = "occlusion_right"; // right pixels visible in the left view
inline constexpr const char* kNormalRightFolder = "normal_right";       // the right view's normals (stereo)
inline constexpr const char* kRangeFolder = "range"; // range sensors: range/<sensor>/ (range/range_files.h)
inline constexpr const char* kMotionBlurFolder = "motion_blur"; // with a shutter: left blur length, pixels, float EXR
inline constexpr const char* kAutoExposureFolder = "auto_exposure"; // auto-exposure: meter and factor, JSON
inline constexpr const char* kRawFolder = "raw";             // with a bit depth: left digital numbers, RGB PNG
inline constexpr const char* kRawRightFolder = "raw_right"; // the right view's (stereo)
// Motion ground truth (scene key render.flow; dataset/flow_truth.h): flow_forward/NNNNNN.{flo,png,exr} is the left
// view's flow from frame NNNNNN to the next (io/flow_files.h); its mask: 255 visible in both frames, 128 occluded or
// out of view, 0 no truth. The same towards the previous frame (flow_backward/; frame 0 has none) and for the right
// view (flowFolders); stereo: the left view's disparity change (.pfm).
inline constexpr const char* kFlowForwardFolder = "flow_forward";
inline constexpr const char* kFlowForwardMaskFolder = "flow_forward_mask";
inline constexpr const char* kFlowBackwardFolder = "flow_backward";
inline constexpr const char* kFlowBackwardMaskFolder = "flow_backward_mask";
inline constexpr const char* kFlowForwardRightFolder = "flow_forward_right";
inline constexpr const char* kFlowForwardMaskRightFolder = "flow_forward_mask_right";
inline constexpr const char* kFlowBackwardRightFolder = "flow_backward_right";
inline constexpr const char* kFlowBackwardMaskRightFolder = "flow_backward_mask_right";
inline constexpr const char* kDisparityChangeForwardFolder = "disparity_change_forward";
inline constexpr const char* kDisparityChangeBackwardFolder = "disparity_change_backward";
struct FlowFolders {
    const char* flow; // kFlowForwardFolder, ...
    const char* mask; // kFlowForwardMaskFolder, ...
};
FlowFolders flowFolders(bool right, bool forward);

// Files of a dataset as a whole.
inline constexpr const char* kCalibFile = "calib.txt";
inline constexpr const char* kFrameLogFile = "frames.jsonl";
inline constexpr const char* kManifestFile = "manifest.json";
inline constexpr const char* kDatasetFile = "dataset.json"; // the fingerprint (dataset/fingerprint.h)
inline constexpr const char* kSceneCopyFile = "scene.json";  // the scene file's bytes ("{}" for the built-in one)
inline constexpr const char* kClassesFile = "classes.json";  // the class table below, as JSON
// "manifest.shard-I-of-N.json": the manifest a `--shard I/N` run writes instead of kManifestFile.
std::string shardManifestName(uint32_t index, uint32_t count);

// "000042": the zero-padded frame number that names every per-frame file.
std::string frameName(uint32_t frame);
// The frame a file stem names: exactly six digits ("000042" -> 42); nullopt for anything else.
std::optional<uint32_t> frameNumber(std::string_view stem);
// "<folder>/<frameName(frame)><extension>", relative to the dataset root; `extension` includes the dot.
std::string frameFile(const char* folder, uint32_t frame, const char* extension);
// The files of range sensor `name` for one frame, relative to the root (range/range_files.h): "range/<name>/NNNNNN"
// with .ply .bin .label (LiDAR), .json .ply (scanner) or .exr (ToF).
std::vector<std::string> rangeFrameFiles(const std::string& name, RangeSensorType type, uint32_t frame);

// One semantic class of semantic/NNNNNN.png, as gpu::kSemantic* numbers it.
struct SemanticClass {
    uint32_t id;       // the pixel value (gpu::kSemantic*)
    const char* name;  // "sky", "ground", "vegetation category 0", ..., "object", "felled", "cut", "turf"
    const char* group; // the broad class: "sky", "ground" (ground, turf), "vegetation" (2..5, felled, cut) or "object"
    uint8_t colour[3]; // sRGB colour for pictures and point clouds (classes.json)
};

// Every class a dataset can hold, by increasing id.
std::span<const SemanticClass> semanticClasses();
// The class with pixel value `id`, or nullptr for a value no class uses.
const SemanticClass* findSemanticClass(uint32_t id);
// classes.json: {"format": "sward-classes-1", "classes": [{"id", "name", "group", "colour": [r, g, b]
// (, "category": k, "scene_name": name)}], "instances": how instance ids are numbered}. `categoryNames` are the
// scene's vegetation category names (index = category): each present category gets its "scene_name".
std::string classesFileText(std::span<const std::string> categoryNames);

} // namespace sward

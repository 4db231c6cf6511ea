// Dataset files written by sward-render (layout and conventions: docs/dataset-format.md).
//
// Per frame NNNNNN: left/ right/ (HDR colour EXR), depth/ (planar metres, +inf sky), disparity/ (EXR, PFM, KITTI
// PNG), semantic/ (uint8 class PNG), instance/ (float EXR ids), preview/ preview_right/ (tonemapped PNG).
// Per dataset: calib.txt, frames.jsonl, manifest.json (or manifest.shard-I-of-N.json). Names: dataset/naming.h.
// Every file is written atomically, so a file that exists is complete; a frame whose files all exist is
// skipped by a re-run (resume), and an interrupted run leaves only "*.tmp" files, removed on the next run.
#pragma once

#include "dataset/frame_images.h"
#include "world/camera.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace sward {

// Frames [first, end) split into `count` contiguous blocks; block `index` is [first', end'). Blocks may be
// empty when there are more shards than frames.
void shardRange(uint32_t first, uint32_t end, uint32_t index, uint32_t count, uint32_t& shardFirst, uint32_t& shardEnd);
// Parses "I/N" (0 <= I < N <= kFrameLimit, digits only); throws a clear error otherwise.
void parseShard(const std::string& text, uint32_t& index, uint32_t& count);

class DatasetWriter {
public:
    DatasetWriter(std::string root, bool stereo);

    // Creates the folders (checking they are writable) and removes temporaries an interrupted run left.
    void prepare() const;
    // Paths of a frame's files relative to the root, in a fixed order.
    std::vector<std::string> frameFiles(uint32_t frame) const;
    bool frameComplete(uint32_t frame) const;
    // Paths of the per-dataset files (frames.jsonl, and calib.txt for stereo) relative to the root.
    std::vector<std::string> datasetFiles() const;

    // Writes every file of one rendered frame. `left` is the reference camera and `baseline` the rig's (metres),
    // for the disparity; `images.labels` hold (class << 24) | instance per pixel (gpu::kSemantic*).
    void writeFrame(uint32_t frame, const FrameImages& images, const Camera& left, double baseline) const;

    // calib.txt (Middlebury 2014): the rig's intrinsics, baseline in millimetres, ndisp covering minDepth.
    void writeCalib(const Camera& left, double baseline, double minDepth) const;
    // frames.jsonl: one record per line, in frame order.
    void writeFrameLog(const std::vector<nlohmann::json>& records) const;
    // The manifest: `info` plus "files": {relative path: sha256} of `files` (relative paths).
    void writeManifest(const std::string& name, nlohmann::json info, const std::vector<std::string>& files) const;

private:
    std::vector<std::string> directories() const;
    std::string root_;
    bool stereo_;
};

} // namespace sward

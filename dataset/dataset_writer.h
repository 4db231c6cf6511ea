// Dataset files written by sward-render (layout and conventions: docs/dataset-format.md).
//
// Per frame NNNNNN: left/ right/ (HDR colour EXR), depth/ (planar metres, +inf sky), disparity/ (EXR, PFM, KITTI
// PNG), semantic/ (uint8 class PNG), instance/ (float EXR ids), normal/ (camera-frame normals, float RGB EXR),
// preview/ preview_right/ (tonemapped PNG); stereo
// also depth_right/, disparity_right/ (EXR, PFM), normal_right/ and occlusion/ occlusion_right/
// (dataset/occlusion.h).
// Per dataset: dataset.json (the fingerprint, dataset/fingerprint.h), calib.txt, frames.jsonl, scene.json (a copy
// of the scene file), classes.json, manifest.json (or manifest.shard-I-of-N.json). Names: dataset/naming.h.
//
// Life of a run: check() (writes nothing) -> lock() -> begin() -> writes -> on failure discardCreated(). Every
// file is written atomically (common/atomic_file.h), so a file that exists is complete; since a folder only ever
// holds files of one fingerprint, a frame whose files all exist is skipped by a re-run (resume). A run that fails
// removes what it created and keeps what earlier runs finished; a killed run leaves complete files only. The lock
// file (.sward.lock) is no dataset file: never listed, hashed or compared, and gone after the last writer.
#pragma once

#include "common/atomic_file.h"
#include "common/output_lock.h"
#include "dataset/frame_images.h"
#include "dataset/frame_truth.h"
#include "scene/range_sensors.h"
#include "world/camera.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace sward {

// Frames [first, end) split into `count` contiguous blocks; block `index` is [first', end'). Blocks may be
// empty when there are more shards than frames.
void shardRange(uint32_t first, uint32_t end, uint32_t index, uint32_t count, uint32_t& shardFirst, uint32_t& shardEnd);
// Parses "I/N" (0 <= I < N <= kFrameLimit, digits only); throws a clear error otherwise.
void parseShard(const std::string& text, uint32_t& index, uint32_t& count);

// The frames before and after a frame, whose truth tells where its pixels' points are visible (render.flow).
struct FlowNeighbours {
    const FrameImages* previous = nullptr; // null for frame 0 (no backward flow)
    const FrameImages* next = nullptr;
};

class DatasetWriter {
public:
    // `rangeSensors`: the scene's range sensors, whose files (range/<name>/) belong to each frame. `flow`: frames have
    // the motion ground truth files too (render.flow; dataset/flow_truth.h).
    // `motionBlur`: frames have the motion_blur/ file (a shutter: FrameImages::motionBlur).
    // `autoExposure`: frames have the auto_exposure/NNNNNN.json file (FrameImages::autoExposure).
    // `rawBitDepth`: frames have raw/NNNNNN.png (and raw_right/) of that many bits (FrameImages::raw); 0: none.
    DatasetWriter(std::string root, bool stereo, const std::vector<RangeSensorParams>& rangeSensors = {},
                  bool flow = false, bool motionBlur = false, bool autoExposure = false, uint32_t rawBitDepth = 0);

    // Checks, writing nothing, that the run can start: the output folder (or, when missing, its nearest existing
    // parent) is a writable folder; no name the dataset uses in it is a symbolic link (sward never writes, hashes or
    // removes through one; --out itself may be a link: the user chose it); a dataset already there has
    // `fingerprint` (keys absent from it are not compared), unless `overwrite`; and its file system has
    // `bytesNeeded` bytes free. Before all that, that no other writer holds the folder against a `shared` (or an
    // exclusive) writer (lock()): a second writer's error names the first one, not the half-written state it sees.
    // Throws one clear error.
    void check(const nlohmann::json& fingerprint, bool overwrite, uint64_t bytesNeeded, bool shared = false) const;
    // An upper bound of the bytes one frame's files take on disk at `width` x `height`, for the free-space check.
    uint64_t frameBytesUpperBound(uint32_t width, uint32_t height) const;
    // Throws, writing nothing, when another writer holds the folder `root` against this one (lock()): a run asks
    // before any work, so a second writer fails at once.
    static void requireNoOtherWriter(const std::string& root, bool shared);
    // Takes the output folder for this run (common/output_lock.h), creating it and its missing parents (removed
    // again by discardCreated): shared for one of several shards of a run (`--shard` without --overwrite, which
    // write one folder together), exclusive otherwise. Throws naming the holder's pid when another writer has it.
    // Held until the writer is destroyed.
    void lock(bool shared);
    // Starts writing (after lock()): with `overwrite` first removes the old dataset's files (sward's files only, never foreign
    // ones); creates the folders, removes sward temporaries that dead processes left, and creates dataset.json
    // (a concurrent shard's must have the same fingerprint).
    void begin(const nlohmann::json& fingerprint, bool overwrite);
    // Removes every file and folder this writer created (after a failed run): the folder is left as it was found,
    // apart from files an --overwrite removed. Never throws.
    void discardCreated() noexcept;

    // Paths of a frame's files relative to the root, in a fixed order.
    std::vector<std::string> frameFiles(uint32_t frame) const;
    bool frameComplete(uint32_t frame) const;
    // Paths of the per-dataset files (frames.jsonl, scene.json, classes.json, and calib.txt for stereo) relative
    // to the root.
    std::vector<std::string> datasetFiles() const;

    // Writes every file of one rendered frame. `left` is the reference camera and `baseline` the rig's (metres),
    // for the disparity; `images.labels` hold (class << 24) | instance per pixel (gpu::kSemantic*).
    // A writer with flow needs `flow`: the neighbouring frames rendered with flow too.
    void writeFrame(uint32_t frame, const FrameImages& images, const Camera& left, double baseline,
                    const FlowNeighbours* flow = nullptr);
    // The absolute path under which to write the frame file `relative` (one of frameFiles(): a range sensor's files,
    // written by range/range_files.h), remembered as created by this run when it does not exist yet.
    std::string claim(const std::string& relative);

    // The per-dataset files are functions of the fingerprint, so each is written only when missing.
    // calib.txt (Middlebury 2014): the rig's intrinsics, baseline in millimetres, ndisp covering minDepth.
    void writeCalib(const Camera& left, double baseline, double minDepth);
    // scene.json (`sceneText`: the scene file's bytes) and classes.json (`classesText`, naming.h): a dataset
    // carries its own scene and class table.
    void writeSceneFiles(const std::string& sceneText, const std::string& classesText);
    // frames.jsonl: one record per line, in frame order.
    void writeFrameLog(const std::vector<nlohmann::json>& records);
    // The manifest: `info` plus "files": {relative path: sha256} of `files` (relative paths); rewritten only
    // when its content changes.
    void writeManifest(const std::string& name, nlohmann::json info, const std::vector<std::string>& files);

private:
    std::vector<std::string> directories() const;
    // The stereo files of writeFrame: right colour, both views' disparity and depth, occlusion masks, right normals.
    void writeStereoFiles(uint32_t frame, const FrameImages& images, const FrameTruth& truth);
    // The motion ground truth files of writeFrame; `focalBaseline` f*B (stereo) for the disparity change.
    void writeFlowFiles(uint32_t frame, const FrameImages& images, const FlowNeighbours& neighbours,
                        double focalBaseline);
    std::vector<std::string> flowFiles(uint32_t frame) const;
    // The absolute path of `relative`, remembered as created by this run when no file of that name exists yet.
    std::string target(const std::string& relative);
    void createFolder(const std::string& path);
    // Creates the root folder and its missing parents (each recorded as created, so a failed run removes them).
    void createRoot();
    void removeOldDataset() const;
    void requireNoLinks() const;
    std::string root_;
    bool stereo_, flow_, motionBlur_, autoExposure_;
    uint32_t rawBitDepth_;
    struct RangeFiles {
        std::string name;
        RangeSensorType type;
        uint64_t beams; // per sweep
    };
    std::vector<RangeFiles> rangeSensors_;
    std::vector<std::string> createdFiles_, createdFolders_;
    std::unique_ptr<OutputLock> lock_;
    std::unique_ptr<OutputRoot> outputRoot_; // from begin(): every file below root_ is written through no link
};

} // namespace sward

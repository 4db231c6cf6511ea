#include "dataset/dataset_writer.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/half_float.h"
#include "common/parse_number.h"
#include "dataset/fingerprint.h"
#include "dataset/flow_truth.h"
#include "dataset/frame_truth.h"
#include "dataset/naming.h"
#include "dataset/occlusion.h"
#include "io/disparity_files.h"
#include "io/image_files.h"
#include "io/sha256.h"
#include "scene/camera_rig.h"
#include "shared/gpu_layout.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <regex>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

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

namespace {

// Every folder a dataset may have, whatever its rig: --overwrite clears them all.
// clang-format off
constexpr const char* kAllFolders[] = {
    kLeftFolder,        kRightFolder,         kDepthFolder,          kDisparityFolder,      kSemanticFolder,
    kInstanceFolder,    kPreviewFolder,       kPreviewRightFolder,   kDepthRightFolder,     kDisparityRightFolder,
    kOcclusionFolder,   kOcclusionRightFolder, kNormalFolder,        kNormalRightFolder,
    kFlowForwardFolder, kFlowForwardMaskFolder, kFlowBackwardFolder, kFlowBackwardMaskFolder,
    kFlowForwardRightFolder, kFlowForwardMaskRightFolder, kFlowBackwardRightFolder, kFlowBackwardMaskRightFolder,
    kDisparityChangeForwardFolder, kDisparityChangeBackwardFolder, kMotionBlurFolder};
// clang-format on

bool isSwardTemporaryName(const std::string& name) {
    long pid = 0;
    return isSwardTemporary(name, pid);
}

// The files sward-render writes at the root of a dataset (temporaries aside).
bool isRootDatasetFile(const std::string& name) {
    static const std::regex shardManifest(R"(manifest\.shard-\d+-of-\d+\.json)");
    return name == kDatasetFile || name == kManifestFile || name == kCalibFile || name == kFrameLogFile ||
           name == kSceneCopyFile || name == kClassesFile || std::regex_match(name, shardManifest);
}

// NNNNNN.exr / .png / .pfm: the per-frame files of a dataset folder.
bool isFrameFileName(const fs::path& name) {
    const std::string extension = name.extension().string();
    return frameNumber(name.stem().string()) && (extension == ".exr" || extension == ".png" || extension == ".pfm");
}

// NNNNNN.ply / .bin / .label / .json / .exr: a range sensor's per-frame files (range/<sensor>/).
bool isRangeFileName(const fs::path& name) {
    const std::string extension = name.extension().string();
    return frameNumber(name.stem().string()) && (extension == ".ply" || extension == ".bin" || extension == ".label" ||
                                                 extension == ".json" || extension == ".exr");
}

// The sensor folders under range/ ("range/<name>"), whatever their names.
std::vector<std::string> rangeFoldersIn(const std::string& root) {
    std::vector<std::string> folders;
    std::error_code ec;
    for (const fs::directory_entry& entry : fs::directory_iterator(root + "/" + kRangeFolder, ec))
        if (entry.is_directory(ec) && !entry.is_symlink(ec))
            folders.push_back(std::string(kRangeFolder) + "/" + entry.path().filename().string());
    std::sort(folders.begin(), folders.end());
    return folders;
}

// Relative paths of the sward dataset files under `root` (with sward temporaries when `withTemporaries`);
// foreign files are never listed.
std::vector<std::string> swardFilesIn(const std::string& root, bool withTemporaries) {
    std::vector<std::string> files;
    std::error_code ec;
    auto scan = [&](const std::string& folder, bool (*isOurs)(const fs::path&)) {
        const std::string dir = folder.empty() ? root : root + "/" + folder;
        if (fs::is_symlink(dir, ec)) return; // never listed through (check() refuses it)
        for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
            const std::string name = entry.path().filename().string();
            const bool ours = isOurs(entry.path().filename());
            if ((ours && !entry.is_directory(ec)) || (withTemporaries && isSwardTemporaryName(name)))
                files.push_back(folder.empty() ? name : folder + "/" + name);
        }
    };
    scan("", [](const fs::path& name) { return isRootDatasetFile(name.string()); });
    for (const char* folder : kAllFolders) scan(folder, isFrameFileName);
    for (const std::string& folder : rangeFoldersIn(root)) scan(folder, isRangeFileName);
    return files;
}

constexpr const char* kUseOverwrite = "; use --overwrite to start over or choose another --out";

bool isDatasetFolder(const std::string& name) {
    return name == kRangeFolder ||
           std::any_of(std::begin(kAllFolders), std::end(kAllFolders), [&](const char* f) { return name == f; });
}

[[noreturn]] void refuseLink(const std::string& path) {
    throw Error("'" + path +
                "' is a symbolic link: sward never writes through links in an output folder; remove it "
                "or choose another --out");
}

// Refuses a link among the entries of `dir` that `isOurs` names (a link to a folder is listed, never entered).
void refuseLinksIn(const std::string& dir, const std::function<bool(const std::string&)>& isOurs) {
    std::error_code ec;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec))
        if (entry.is_symlink(ec) && isOurs(entry.path().filename().string())) refuseLink(entry.path().string());
}

} // namespace

DatasetWriter::DatasetWriter(std::string root, bool stereo, const std::vector<RangeSensorParams>& rangeSensors,
                             bool flow, bool motionBlur, bool autoExposure, uint32_t rawBitDepth)
    : root_(std::move(root)), stereo_(stereo), flow_(flow), motionBlur_(motionBlur), autoExposure_(autoExposure),
      rawBitDepth_(rawBitDepth) {
    for (const RangeSensorParams& sensor : rangeSensors)
        rangeSensors_.push_back({sensor.name, sensor.type, sensor.channels() * uint64_t(sensor.columns())});
}

std::vector<std::string> DatasetWriter::directories() const {
    std::vector<std::string> dirs = {kLeftFolder,     kDepthFolder,  kSemanticFolder,
                                     kInstanceFolder, kNormalFolder, kPreviewFolder};
    if (stereo_)
        dirs.insert(dirs.end(), {kRightFolder, kDisparityFolder, kPreviewRightFolder, kDepthRightFolder,
                                 kDisparityRightFolder, kOcclusionFolder, kOcclusionRightFolder, kNormalRightFolder});
    for (uint32_t view = 0; flow_ && view < (stereo_ ? 2u : 1u); ++view)
        for (bool forward : {true, false})
            dirs.insert(dirs.end(), {flowFolders(view == 1, forward).flow, flowFolders(view == 1, forward).mask});
    if (flow_ && stereo_) dirs.insert(dirs.end(), {kDisparityChangeForwardFolder, kDisparityChangeBackwardFolder});
    if (motionBlur_) dirs.push_back(kMotionBlurFolder);
    if (autoExposure_) dirs.push_back(kAutoExposureFolder);
    if (rawBitDepth_ != 0) dirs.push_back(kRawFolder);
    if (rawBitDepth_ != 0 && stereo_) dirs.push_back(kRawRightFolder);
    if (!rangeSensors_.empty()) dirs.push_back(kRangeFolder);
    for (const RangeFiles& sensor : rangeSensors_) dirs.push_back(std::string(kRangeFolder) + "/" + sensor.name);
    return dirs;
}

void DatasetWriter::requireNoOtherWriter(const std::string& root, bool shared) {
    std::error_code ec;
    if (fs::is_directory(root, ec))
        OutputLock::requireFree(root, shared ? OutputLock::Mode::Shared : OutputLock::Mode::Exclusive);
}

void DatasetWriter::check(const nlohmann::json& fingerprint, bool overwrite, uint64_t bytesNeeded, bool shared) const {
    std::error_code ec;
    if (!lock_) requireNoOtherWriter(root_, shared); // once this writer holds the folder, the holder is itself
    fs::path existing = fs::absolute(root_, ec);
    while (!fs::exists(existing, ec) && existing.has_relative_path()) existing = existing.parent_path();
    if (!fs::is_directory(existing, ec))
        throw Error("cannot create output folder '" + root_ + "': '" + existing.string() + "' is not a folder");
    if (::access(existing.c_str(), W_OK | X_OK) != 0)
        throw Error("cannot write to output folder '" + root_ + "': " + ioErrorReason(errno));
    requireNoLinks();
    const std::string description = root_ + "/" + kDatasetFile;
    if (!overwrite && fs::exists(description, ec)) {
        const std::string difference = fingerprintDifference(readDatasetFingerprint(description), fingerprint);
        if (!difference.empty()) throw Error("'" + root_ + "' " + difference + kUseOverwrite);
    } else if (!overwrite && fs::is_directory(root_, ec) && !swardFilesIn(root_, false).empty()) {
        throw Error("'" + root_ + "' holds dataset files but no " + kDatasetFile +
                    " saying how they were rendered (made by an older sward?)" + kUseOverwrite);
    }
    struct statvfs space;
    if (::statvfs(existing.c_str(), &space) == 0 && uint64_t(space.f_bavail) * space.f_frsize < bytesNeeded)
        throw Error("not enough space in '" + root_ + "' for one frame: it needs up to " + std::to_string(bytesNeeded) +
                    " bytes, the file system has " + std::to_string(uint64_t(space.f_bavail) * space.f_frsize) +
                    " free");
}

uint64_t DatasetWriter::frameBytesUpperBound(uint32_t width, uint32_t height) const {
    // Raw bytes per pixel of each file: colour half RGBA, depth Y+Z, semantic, instance, normal float RGB, preview
    // RGB; stereo adds right colour, disparity EXR, PFM, KITTI 16-bit PNG, right preview, right depth Y+Z, right
    // disparity EXR and PFM, the two occlusion masks and the right normals. Deflate (EXR ZIP, PNG) can expand
    // incompressible data by up to 1/8 (stb's fixed Huffman codes); each file gets a row byte per line and 4 KiB
    // of headers and tables, and is rounded up to 4 KiB blocks plus one for the file system's own records.
    std::vector<uint64_t> bytesPerPixel = {8, 8, 1, 4, 12, 3};
    if (stereo_) bytesPerPixel.insert(bytesPerPixel.end(), {8, 4, 4, 2, 3, 8, 4, 4, 1, 1, 12});
    // Flow, per view and direction: .flo 8, KITTI PNG 6, EXR 12, mask 1; stereo: two disparity changes of 4.
    for (uint32_t k = 0; flow_ && k < (stereo_ ? 4u : 2u); ++k)
        bytesPerPixel.insert(bytesPerPixel.end(), {8, 6, 12, 1});
    if (flow_ && stereo_) bytesPerPixel.insert(bytesPerPixel.end(), {4, 4});
    if (motionBlur_) bytesPerPixel.push_back(4); // the blur length, float Y
    if (autoExposure_) bytesPerPixel.push_back(0); // a line of JSON: its header allowance and blocks
    for (uint32_t view = 0; rawBitDepth_ != 0 && view < (stereo_ ? 2u : 1u); ++view)
        bytesPerPixel.push_back(rawBitDepth_ > 8 ? 6 : 3); // the digital numbers, RGB PNG of 8 or 16 bits
    constexpr uint64_t kBlock = 4096;
    uint64_t total = 0;
    for (uint64_t perPixel : bytesPerPixel) {
        const uint64_t bytes = perPixel * width * height * 9 / 8 + height + kBlock;
        total += (bytes + kBlock - 1) / kBlock * kBlock + kBlock;
    }
    // Range sensors, per beam: PLY 53 + KITTI 16 + label 4 bytes, or a scan's JSON (at most 16 characters a range) and
    // PLY, or a ToF pixel's Y + Z; each file with its header and blocks.
    for (const RangeFiles& sensor : rangeSensors_) {
        const uint64_t perBeam = sensor.type == RangeSensorType::Lidar     ? 73
                                 : sensor.type == RangeSensorType::Scanner ? 69
                                                                           : 9;
        total += sensor.beams * perBeam + 4 * (kBlock + kBlock);
    }
    return total;
}

void DatasetWriter::createFolder(const std::string& path) {
    if (::mkdir(path.c_str(), 0777) == 0) {
        createdFolders_.push_back(path);
        return;
    }
    const int error = errno;
    struct stat info; // a link of that name is no folder of ours (requireNoLinks names it first)
    if (error == EEXIST && ::lstat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode))
        return; // made earlier, or by a concurrent shard
    throw Error("cannot create output folder '" + path + "': " + ioErrorReason(error));
}

void DatasetWriter::requireNoLinks() const {
    // The dataset's own names only: a foreign link beside them is left alone, like every foreign file.
    refuseLinksIn(root_, [](const std::string& name) {
        return isRootDatasetFile(name) || isDatasetFolder(name) || isSwardTemporaryName(name) || isOutputLockFile(name);
    });
    auto frameOrTemporary = [](const std::string& name) {
        return isFrameFileName(name) || isRangeFileName(name) || isSwardTemporaryName(name);
    };
    std::error_code ec;
    for (const char* folder : kAllFolders)
        if (fs::is_directory(root_ + "/" + folder, ec)) refuseLinksIn(root_ + "/" + folder, frameOrTemporary);
    const std::string range = root_ + "/" + kRangeFolder;
    if (!fs::is_directory(range, ec)) return;
    refuseLinksIn(range, [](const std::string&) { return true; }); // every sensor folder is the dataset's
    for (const std::string& folder : rangeFoldersIn(root_)) refuseLinksIn(root_ + "/" + folder, frameOrTemporary);
}

void DatasetWriter::createRoot() {
    std::vector<fs::path> missing; // the root and its missing parents, innermost first
    std::error_code ec;
    for (fs::path p = fs::path(root_).lexically_normal(); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
        missing.push_back(p);
        if (p.parent_path() == p) break;
    }
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) createFolder(it->string());
}

void DatasetWriter::lock(bool shared) {
    createRoot();
    lock_ = std::make_unique<OutputLock>(root_, shared ? OutputLock::Mode::Shared : OutputLock::Mode::Exclusive);
}

void DatasetWriter::removeOldDataset() const {
    std::error_code ec;
    for (const std::string& file : swardFilesIn(root_, true)) {
        struct stat info; // regular files only: a link (refused before) or a folder of that name is not removed
        const std::string path = root_ + "/" + file;
        if (::lstat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode)) ::unlink(path.c_str());
    }
    for (const std::string& folder : rangeFoldersIn(root_)) fs::remove(root_ + "/" + folder, ec);
    fs::remove(root_ + "/" + kRangeFolder, ec);
    for (const char* folder : kAllFolders) fs::remove(root_ + "/" + folder, ec); // only when left empty
}

void DatasetWriter::begin(const nlohmann::json& fingerprint, bool overwrite) {
    std::error_code ec;
    requireNoLinks(); // again, now that this run holds the folder
    if (overwrite && fs::is_directory(root_, ec)) removeOldDataset();
    createRoot();
    for (const std::string& dir : directories()) createFolder(root_ + "/" + dir);
    requireNoLinks(); // a link made meanwhile in place of a folder
    // From here on every file is written relative to a handle on the folder, following no link below it: a link
    // swapped in for left/ while the render runs is refused at the next write, not followed out of --out.
    outputRoot_ = std::make_unique<OutputRoot>(root_);
    removeStaleTemporaries(root_);
    for (const std::string& dir : directories()) removeStaleTemporaries(root_ + "/" + dir);

    // Exclusive creation: of several shards starting together one writes it and the others compare.
    const std::string description = root_ + "/" + kDatasetFile;
    if (createFileExclusively(description, datasetFileText(fingerprint))) {
        createdFiles_.push_back(description);
        return;
    }
    const std::string difference = fingerprintDifference(readDatasetFingerprint(description), fingerprint);
    require(difference.empty(), "'" + root_ + "' " + difference + kUseOverwrite);
}

void DatasetWriter::discardCreated() noexcept {
    for (auto it = createdFiles_.rbegin(); it != createdFiles_.rend(); ++it) ::unlink(it->c_str());
    for (auto it = createdFolders_.rbegin(); it != createdFolders_.rend(); ++it) ::rmdir(it->c_str());
    // The root holds the lock file until the lock goes (the last holder removes it): then the root and the parents
    // this run made are empty too.
    lock_.reset();
    for (auto it = createdFolders_.rbegin(); it != createdFolders_.rend(); ++it) ::rmdir(it->c_str());
    createdFiles_.clear();
    createdFolders_.clear();
}

std::string DatasetWriter::claim(const std::string& relative) {
    return target(relative);
}

std::string DatasetWriter::target(const std::string& relative) {
    std::string path = root_ + "/" + relative;
    struct stat info;
    if (::lstat(path.c_str(), &info) != 0) createdFiles_.push_back(path);
    return path;
}

std::vector<std::string> DatasetWriter::frameFiles(uint32_t frame) const {
    std::vector<std::string> files = {
        frameFile(kLeftFolder, frame, ".exr"),     frameFile(kDepthFolder, frame, ".exr"),
        frameFile(kSemanticFolder, frame, ".png"), frameFile(kInstanceFolder, frame, ".exr"),
        frameFile(kNormalFolder, frame, ".exr"),   frameFile(kPreviewFolder, frame, ".png")};
    if (stereo_)
        files.insert(files.end(),
                     {frameFile(kRightFolder, frame, ".exr"), frameFile(kDisparityFolder, frame, ".exr"),
                      frameFile(kDisparityFolder, frame, ".pfm"), frameFile(kDisparityFolder, frame, ".png"),
                      frameFile(kPreviewRightFolder, frame, ".png"), frameFile(kDepthRightFolder, frame, ".exr"),
                      frameFile(kDisparityRightFolder, frame, ".exr"), frameFile(kDisparityRightFolder, frame, ".pfm"),
                      frameFile(kOcclusionFolder, frame, ".png"), frameFile(kOcclusionRightFolder, frame, ".png"),
                      frameFile(kNormalRightFolder, frame, ".exr")});
    if (motionBlur_) files.push_back(frameFile(kMotionBlurFolder, frame, ".exr"));
    if (autoExposure_) files.push_back(frameFile(kAutoExposureFolder, frame, ".json"));
    if (rawBitDepth_ != 0) files.push_back(frameFile(kRawFolder, frame, ".png"));
    if (rawBitDepth_ != 0 && stereo_) files.push_back(frameFile(kRawRightFolder, frame, ".png"));
    for (const RangeFiles& sensor : rangeSensors_)
        for (std::string& file : rangeFrameFiles(sensor.name, sensor.type, frame)) files.push_back(std::move(file));
    for (std::string& file : flowFiles(frame)) files.push_back(std::move(file));
    return files;
}

std::vector<std::string> DatasetWriter::flowFiles(uint32_t frame) const {
    std::vector<std::string> files;
    if (!flow_) return files;
    for (uint32_t view = 0; view < (stereo_ ? 2u : 1u); ++view)
        for (bool forward : {true, false}) {
            if (!forward && frame == 0) continue;
            const FlowFolders folders = flowFolders(view == 1, forward);
            for (const char* extension : {".flo", ".png", ".exr"})
                files.push_back(frameFile(folders.flow, frame, extension));
            files.push_back(frameFile(folders.mask, frame, ".png"));
        }
    if (stereo_) {
        files.push_back(frameFile(kDisparityChangeForwardFolder, frame, ".pfm"));
        if (frame > 0) files.push_back(frameFile(kDisparityChangeBackwardFolder, frame, ".pfm"));
    }
    return files;
}

std::vector<std::string> DatasetWriter::datasetFiles() const {
    std::vector<std::string> files = {kFrameLogFile, kSceneCopyFile, kClassesFile};
    if (stereo_) files.push_back(kCalibFile);
    return files;
}

bool DatasetWriter::frameComplete(uint32_t frame) const {
    for (const std::string& file : frameFiles(frame))
        if (!fs::is_regular_file(root_ + "/" + file)) return false;
    return true;
}

void DatasetWriter::writeFrame(uint32_t frame, const FrameImages& images, const Camera& left, double baseline,
                               const FlowNeighbours* flow) {
    require(!flow_ || (flow && flow->next && (frame == 0 || flow->previous) && !images.flowForward.empty()),
            "DatasetWriter::writeFrame: a dataset with flow needs each frame's flow and its neighbours");
    const uint32_t w = images.width, h = images.height;
    auto path = [&](const char* folder, const char* extension) { return target(frameFile(folder, frame, extension)); };

    const FrameTruth truth = frameTruth(images, left.fx, stereo_ ? baseline : 0.0);
    writeExrRgbaHalf(path(kLeftFolder, ".exr"), w, h, colourWithCoverage(images.rgbaHalf));
    writeExrDepth(path(kDepthFolder, ".exr"), w, h, images.depth);
    writePng8(path(kSemanticFolder, ".png"), w, h, 1, truth.semantic);
    if (truth.tile.empty())
        writeExrFloatChannels(path(kInstanceFolder, ".exr"), w, h, {"Y"}, {truth.instance});
    else
        writeExrFloatChannels(path(kInstanceFolder, ".exr"), w, h, {"Y", "tile"}, {truth.instance, truth.tile});
    writeExr(path(kNormalFolder, ".exr"), w, h, 3, images.normals); // channels R, G, B = camera x, y, z
    writePng8(path(kPreviewFolder, ".png"), w, h, 3, tonemapPreview(images.rgbaHalf, w, h));
    if (stereo_) writeStereoFiles(frame, images, truth);
    if (flow_) writeFlowFiles(frame, images, *flow, left.fx * baseline);
    if (motionBlur_) {
        require(images.motionBlur.size() == size_t(w) * h,
                "DatasetWriter::writeFrame: a shutter's frame needs its blur");
        writeExrFloatChannels(path(kMotionBlurFolder, ".exr"), w, h, {"Y"}, {images.motionBlur});
    }
    if (autoExposure_) { // the exposure the frame got, known only once it and its window have rendered
        require(images.autoExposure.has_value(), "DatasetWriter::writeFrame: an auto-exposed frame needs its exposure");
        const nlohmann::json record = {
            {"frame", frame}, {"meter", images.autoExposure->meter}, {"factor", images.autoExposure->factor}};
        writeTextAtomically(path(kAutoExposureFolder, ".json"), record.dump() + "\n");
    }
    for (uint32_t view = 0; rawBitDepth_ != 0 && view < (stereo_ ? 2u : 1u); ++view) {
        const std::vector<uint16_t>& dn = view == 0 ? images.raw : images.rightRaw;
        const uint32_t channels = dn.size() == size_t(w) * h ? 1 : 3; // 1: a Bayer sensor's mosaic (sensor_raw.h)
        require(dn.size() == size_t(w) * h * channels,
                "DatasetWriter::writeFrame: a frame with a bit depth needs its raw");
        const std::string file = path(view == 0 ? kRawFolder : kRawRightFolder, ".png");
        if (rawBitDepth_ > 8) // the DN in the low bits, not shifted up: a 12-bit file's values are 0..4095
            writePng16(file, w, h, channels, dn);
        else
            writePng8(file, w, h, channels, std::vector<uint8_t>(dn.begin(), dn.end()));
    }
}

void DatasetWriter::writeFlowFiles(uint32_t frame, const FrameImages& images, const FlowNeighbours& neighbours,
                                   double focalBaseline) {
    const uint32_t w = images.width, h = images.height;
    for (uint32_t view = 0; view < (stereo_ ? 2u : 1u); ++view)
        for (bool forward : {true, false}) {
            const FrameImages* other = forward ? neighbours.next : neighbours.previous;
            if (!other) continue; // frame 0: no backward flow
            const bool right = view == 1;
            const std::vector<float>& flow = right ? (forward ? images.rightFlowForward : images.rightFlowBackward)
                                                   : (forward ? images.flowForward : images.flowBackward);
            const FlowTruth truth = flowTruth(w, h, flow, right ? other->rightDepth : other->depth);
            const FlowFolders folders = flowFolders(right, forward);
            writeFlo(target(frameFile(folders.flow, frame, ".flo")), truth.flow);
            writeKittiFlowPng(target(frameFile(folders.flow, frame, ".png")), truth.flow);
            writeExr(target(frameFile(folders.flow, frame, ".exr")), w, h, 3, truth.exr);
            writePng8(target(frameFile(folders.mask, frame, ".png")), w, h, 1, occlusionMaskPixels(truth.visibility));
            if (stereo_ && !right)
                writePfmValues(
                    target(frameFile(forward ? kDisparityChangeForwardFolder : kDisparityChangeBackwardFolder, frame,
                                     ".pfm")),
                    w, h, disparityChange(flow, images.depth, focalBaseline));
        }
}

void DatasetWriter::writeStereoFiles(uint32_t frame, const FrameImages& images, const FrameTruth& truth) {
    const uint32_t w = images.width, h = images.height;
    auto path = [&](const char* folder, const char* extension) { return target(frameFile(folder, frame, extension)); };
    const std::vector<float>& disparity = truth.disparity;
    const std::vector<float>& rightDisparity = truth.rightDisparity;
    writeExrRgbaHalf(path(kRightFolder, ".exr"), w, h, colourWithCoverage(images.rightRgbaHalf));
    writeExrFloatChannels(path(kDisparityFolder, ".exr"), w, h, {"Y"}, {disparity});
    writePfm(path(kDisparityFolder, ".pfm"), w, h, disparity);
    writeKittiPng(path(kDisparityFolder, ".png"), w, h, disparity);
    writePng8(path(kPreviewRightFolder, ".png"), w, h, 3, tonemapPreview(images.rightRgbaHalf, w, h));
    writeExrDepth(path(kDepthRightFolder, ".exr"), w, h, images.rightDepth);
    writeExrFloatChannels(path(kDisparityRightFolder, ".exr"), w, h, {"Y"}, {rightDisparity});
    writePfm(path(kDisparityRightFolder, ".pfm"), w, h, rightDisparity);
    // Each view's mask is the rig's at the view's own time: an unsynchronised rig's other view then (FrameTruth).
    const bool synchronised = truth.rightDisparityAtLeftTime.empty();
    const std::vector<float>& rightThen = synchronised ? rightDisparity : truth.rightDisparityAtLeftTime;
    const std::vector<float>& leftThen = synchronised ? disparity : truth.disparityAtRightTime;
    writePng8(path(kOcclusionFolder, ".png"), w, h, 1,
              occlusionMaskPixels(visibilityInOtherView(w, h, disparity, rightThen, -1)));
    writePng8(path(kOcclusionRightFolder, ".png"), w, h, 1,
              occlusionMaskPixels(visibilityInOtherView(w, h, rightDisparity, leftThen, +1)));
    writeExr(path(kNormalRightFolder, ".exr"), w, h, 3, images.rightNormals);
}

void DatasetWriter::writeCalib(const Camera& left, double baseline, double minDepth) {
    std::error_code ec;
    if (fs::exists(root_ + "/" + kCalibFile, ec)) return;
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
    writeMiddleburyCalib(target(kCalibFile), calib);
}

void DatasetWriter::writeSceneFiles(const std::string& sceneText, const std::string& classesText) {
    std::error_code ec;
    if (!fs::exists(root_ + "/" + kSceneCopyFile, ec)) writeTextAtomically(target(kSceneCopyFile), sceneText);
    if (!fs::exists(root_ + "/" + kClassesFile, ec)) writeTextAtomically(target(kClassesFile), classesText);
}

void DatasetWriter::writeFrameLog(const std::vector<nlohmann::json>& records) {
    std::error_code ec;
    if (fs::exists(root_ + "/" + kFrameLogFile, ec)) return;
    std::string text;
    for (const nlohmann::json& record : records) text += record.dump() + "\n";
    writeTextAtomically(target(kFrameLogFile), text);
}

void DatasetWriter::writeManifest(const std::string& name, nlohmann::json info, const std::vector<std::string>& files) {
    nlohmann::json hashes = nlohmann::json::object();
    for (const std::string& file : files) hashes[file] = sha256File(root_ + "/" + file);
    info["files"] = std::move(hashes);
    const std::string text = info.dump(2) + "\n";
    // An unchanged manifest is not rewritten: a re-run of a complete dataset writes nothing at all.
    std::ifstream old(root_ + "/" + name, std::ios::binary);
    const std::string oldText{std::istreambuf_iterator<char>(old), std::istreambuf_iterator<char>()};
    if (old && oldText == text) return;
    writeTextAtomically(target(name), text);
}

} // namespace sward

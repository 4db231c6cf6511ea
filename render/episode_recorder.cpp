#include "render/episode_recorder.h"

#include "common/error.h"
#include "dataset/fingerprint.h"
#include "dataset/frame_record.h"
#include "dataset/naming.h"
#include "range/range_files.h"

#include <filesystem>

namespace sward {

namespace {

std::unique_ptr<DatasetWriter> writerFor(const SceneResources& r, const std::string& outDir) {
    const SensorParams& sensor = r.scene.camera.rig.sensor;
    return std::make_unique<DatasetWriter>(outDir, r.scene.camera.rig.stereo(), r.scene.rangeSensors, /*flow=*/false,
                                           sensor.enabled && sensor.shutterSeconds > 0.0,
                                           sensor.enabled && sensor.autoExposure.enabled,
                                           sensor.enabled ? sensor.bitDepth : 0);
}

// sward-render's fingerprint keys (render/render_job.cpp), the camera the scene's, and "episode": a folder that holds an
// episode is refused by sward-render (dataset/fingerprint.h), whose runs never carry the key.
nlohmann::json episodeFingerprint(const Session& session, const RenderJobOptions& source) {
    const Scene& scene = session.resources().scene;
    return {{"scene_sha256", datasetSceneHash(source)},
            {"assets", assetHashes(sceneAssets(scene))},
            {"seed", scene.seed},
            {"resolution", std::to_string(session.width()) + "x" + std::to_string(session.height())},
            {"samples", scene.render.samples},
            {"no_vegetation", source.noVegetation},
            {"time", source.time},
            {"camera", nullptr},
            {"look_at", nullptr},
            {"fov_y_deg", nullptr},
            {"sward_revision", datasetRevision()},
            {"device", session.device().name()},
            {"driver", session.device().driver()},
            {"episode", true}};
}

} // namespace

EpisodeRecorder::EpisodeRecorder(Session& session, const RenderJobOptions& source, const std::string& outDir,
                                 bool overwrite)
    : session_(session), source_(source), outDir_(outDir), writer_(writerFor(session.resources(), outDir)) {
    const SceneResources& r = session.resources();
    require(!session.observed(), "record: this simulator is already recording (close that recorder first)");
    require(!r.scene.render.flow, "record: scenes with 'render.flow' cannot be recorded yet (a simulator renders no "
                                  "motion truth); turn it off or write the dataset with write_dataset");
    DatasetWriter::requireNoOtherWriter(outDir, false);
    std::error_code ec;
    require(overwrite || !std::filesystem::exists(std::filesystem::path(outDir) / kDatasetFile, ec),
            "record: '" + outDir +
                "' already holds a dataset; pass overwrite=True to replace it (an episode is never "
                "resumed: its frames come from your program)");
    fingerprint_ = episodeFingerprint(session, source);
    const uint64_t bytes = writer_->frameBytesUpperBound(session.width(), session.height()) + 64 * 1024;
    writer_->check(fingerprint_, overwrite, bytes);
    try {
        writer_->lock(false);
        writer_->begin(fingerprint_, overwrite);
    } catch (...) {
        writer_->discardCreated();
        throw;
    }
    session_.setFrameObserver([this](const SessionFrame& frame) { record(frame); });
}

EpisodeRecorder::~EpisodeRecorder() {
    if (!closed_) session_.setFrameObserver({});
}

void EpisodeRecorder::record(const SessionFrame& frame) {
    if (!frames_.empty() && frame.frame <= frames_.back())
        throw Error("record: frame " + std::to_string(frame.frame) + " comes after frame " +
                    std::to_string(frames_.back()) +
                    " (after a reset or restore_state to an earlier tick, record into a new folder)");
    writer_->writeFrame(frame.frame, frame.images, frame.cameras.left, frame.baseline);
    const std::vector<RangeSensorParams>& sensors = session_.resources().scene.rangeSensors;
    for (size_t k = 0; k < frame.range.size() && k < sensors.size(); ++k)
        writeRangeFiles(*writer_, sensors[k], frame.range[k], frame.frame);
    if (!firstLeft_) firstLeft_ = frame.cameras.left;
    frames_.push_back(frame.frame);
    records_.push_back(frame.record);
}

void EpisodeRecorder::close() {
    if (closed_) return;
    session_.setFrameObserver({});
    closed_ = true;
    const SceneResources& r = session_.resources();
    const RigParams& rig = r.scene.camera.rig;
    if (rig.stereo()) {
        const Camera left =
            firstLeft_ ? *firstLeft_ : sequenceRig(r, session_.width(), session_.height(), session_.frame()).left;
        writer_->writeCalib(left, rig.baseline, rig.minDepth);
    }
    writer_->writeFrameLog(records_);
    writer_->writeSceneFiles(datasetSceneText(source_), datasetClassesText(r.scene));
    std::vector<std::string> files = writer_->datasetFiles();
    for (uint32_t frame : frames_)
        for (std::string& file : writer_->frameFiles(frame)) files.push_back(std::move(file));
    const nlohmann::json options = {{"resolution", fingerprint_["resolution"]},
                                    {"samples", fingerprint_["samples"]},
                                    {"no_vegetation", source_.noVegetation},
                                    {"time", source_.time},
                                    {"episode", true}};
    const std::string scene = source_.sceneText           ? "<scene>"
                              : source_.scenePath.empty() ? "<built-in>"
                                                          : source_.scenePath;
    const nlohmann::json info = {
        {"format", "sward-dataset-1"},
        {"scene", scene},
        {"scene_sha256", fingerprint_["scene_sha256"]},
        {"assets",
         assetManifest(sceneAssets(r.scene), std::filesystem::path(source_.scenePath).parent_path().string())},
        {"units", datasetUnits()},
        {"conventions", datasetConventions()},
        {"seed", r.scene.seed},
        {"frames", frames_.empty() ? nlohmann::json{0, 0} : nlohmann::json{frames_.front(), frames_.back() + 1}},
        {"episode_frames", frames_},
        {"shard", nullptr},
        {"options", options},
        {"sward_revision", fingerprint_["sward_revision"]},
        {"device", fingerprint_["device"]},
        {"driver", fingerprint_["driver"]},
        {"fingerprint", fingerprint_}};
    writer_->writeManifest(kManifestFile, info, files);
    writer_.reset(); // the folder is free for other writers and readers
}

} // namespace sward

// EpisodeRecorder: a driven episode as a dataset (the Python module's Simulator.record, docs/python.md "Drive and
// record"). Attached to a Session (render/session.h), it writes each frame the session renders, as it was rendered,
// through the dataset writer sward-render uses (dataset/dataset_writer.h: the same files, names and atomic writes),
// and the frame's record as the session made it: the poses, the colliders that acted (the program's too) and the
// objects it drove. close() adds frames.jsonl, scene.json, classes.json, calib.txt and the manifest, so the folder is
// a dataset sward's readers and `tools/merge-manifests.py DIR --verify` take.
//
// Rules: an episode is never resumed (its frames come from the program, not the scene), so a folder that holds a
// dataset is refused unless `overwrite`, and sward-render refuses to continue one (the fingerprint's "episode" key);
// frames are recorded in increasing order (a reset or restore_state that goes back needs a new recorder); scenes with
// render.flow are refused (the session renders no motion truth). A recorder destroyed without close() leaves its
// complete frame files and no manifest, as a killed sward-render run does.
#pragma once

#include "dataset/dataset_writer.h"
#include "render/render_job.h"
#include "render/session.h"

#include <nlohmann/json.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sward {

class EpisodeRecorder {
public:
    // Checks and takes the folder `outDir` (nothing is written when a check fails) and attaches to `session`, which
    // must outlive the recorder and have no other recorder. `source` names the scene input the session was built from
    // (scenePath, sceneText, overrides, seed, allowAssets) and its options (noVegetation, time): scene.json, the
    // fingerprint and the manifest say what it says.
    EpisodeRecorder(Session& session, const RenderJobOptions& source, const std::string& outDir, bool overwrite);
    ~EpisodeRecorder();
    EpisodeRecorder(const EpisodeRecorder&) = delete;
    EpisodeRecorder& operator=(const EpisodeRecorder&) = delete;

    // Writes the per-dataset files and the manifest and detaches from the session; a second call does nothing.
    void close();
    bool closed() const { return closed_; }
    const std::vector<uint32_t>& frames() const { return frames_; } // recorded, in order
    const std::string& outDir() const { return outDir_; }

private:
    void record(const SessionFrame& frame);

    Session& session_;
    RenderJobOptions source_;
    std::string outDir_;
    std::unique_ptr<DatasetWriter> writer_; // released by close(), with the folder's lock
    nlohmann::json fingerprint_;
    std::vector<uint32_t> frames_;
    std::vector<nlohmann::json> records_;
    std::optional<Camera> firstLeft_; // calib.txt's camera
    bool closed_ = false;
};

} // namespace sward

// sward-bench dataset: sward-render's whole job timed from inside (render_job.h, RenderJobReport), so the frames
// per second of a dataset, and where its time goes, come from one run.
#include "render/benchmarks.h"

#include "common/error.h"
#include "common/statistics.h"
#include "render/render_job.h"

#include <filesystem>
#include <unistd.h>

namespace sward {

namespace {

// A fresh folder of this process under the system's temporary folder, removed with everything in it at the end.
struct TemporaryFolder {
    std::filesystem::path path;
    TemporaryFolder() {
        path = std::filesystem::temp_directory_path() / ("sward-bench-dataset-" + std::to_string(getpid()));
        std::filesystem::remove_all(path);
        std::filesystem::create_directories(path);
    }
    ~TemporaryFolder() {
        std::error_code ignored;
        std::filesystem::remove_all(path, ignored);
    }
    TemporaryFolder(const TemporaryFolder&) = delete;
    TemporaryFolder& operator=(const TemporaryFolder&) = delete;
};

uint64_t folderBytes(const std::filesystem::path& folder) {
    uint64_t bytes = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(folder))
        if (entry.is_regular_file()) bytes += entry.file_size();
    return bytes;
}

} // namespace

nlohmann::json benchDataset(const DatasetBenchOptions& options) {
    require(options.frames >= 2, "sward-bench dataset: --frames must be at least 2 (the first frame is the warm-up)");
    const TemporaryFolder folder;
    RenderJobOptions job;
    job.scenePath =
        options.scenePath.empty() ? std::string(SWARD_SOURCE_DIR "/examples/rover-track.json") : options.scenePath;
    job.allowAssets = options.allowAssets;
    job.resolution = options.resolution;
    job.samples = options.samples;
    job.device = options.device;
    job.frames = "0:" + std::to_string(options.frames);
    job.outDir = (folder.path / "dataset").string();
    job.quiet = true;
    const RenderJobReport report = runRenderJob(job);
    const std::vector<RenderJobReport::Frame>& f = report.frames;
    require(f.size() == options.frames, "sward-bench dataset: the job rendered " + std::to_string(f.size()) +
                                            " frames, not " + std::to_string(options.frames));

    // The first frame pays for the pipelines' compilation and the caches' first fill: the figures start after it.
    const double frames = double(f.size() - 1);
    const double wall = f.back().doneSeconds - f.front().doneSeconds;
    const double cpu = f.back().cpuSeconds - f.front().cpuSeconds;
    std::vector<double> render, write, wait;
    for (size_t i = 1; i < f.size(); ++i) {
        render.push_back(f[i].renderSeconds);
        write.push_back(f[i].writeSeconds);
        wait.push_back(f[i].waitSeconds);
    }
    return {{"frames_per_second", frames / wall},
            {"seconds_per_frame", wall / frames},
            {"cpu_seconds_per_frame", cpu / frames},
            {"cpu_utilisation", cpu / wall},
            {"render_seconds", median(render)},
            {"write_seconds", median(write)},
            {"wait_seconds", median(wait)},
            {"setup_seconds", report.setupSeconds},
            {"first_frame_seconds", f.front().doneSeconds - report.setupSeconds},
            {"manifest_seconds", report.manifestSeconds},
            {"bytes_per_frame", folderBytes(folder.path / "dataset") / f.size()},
            {"frames", f.size()},
            {"scene", job.scenePath},
            {"resolution", std::to_string(report.width) + "x" + std::to_string(report.height)},
            {"samples", report.samples},
            {"device", report.device}};
}

} // namespace sward

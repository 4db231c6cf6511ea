#include "eval/report.h"

#include "common/atomic_file.h"
#include "dataset/naming.h"
#include "eval/frame_evaluation.h"
#include "eval/number_format.h"
#include "eval/pictures.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>

namespace fs = std::filesystem;

namespace sward {

namespace {

using Json = nlohmann::ordered_json;

void putMetrics(Json& j, const StereoMetrics& m) {
    j["gt_pixels"] = m.gtPixels;
    j["estimated_pixels"] = m.estimatedPixels;
    j["coverage"] = m.coverage;
    j["mean_abs_error"] = m.meanAbsError;
    j["mean_error"] = m.meanError;
    j["std_error"] = m.stdError;
    j["rms"] = m.rms;
    j["max_abs_error"] = m.maxAbsError;
    j["bad_0_5"] = m.bad[0];
    j["bad_1"] = m.bad[1];
    j["bad_2"] = m.bad[2];
    j["bad_4"] = m.bad[3];
    j["a50"] = m.accuracy[0];
    j["a90"] = m.accuracy[1];
    j["a95"] = m.accuracy[2];
    j["a99"] = m.accuracy[3];
    j["d1_all"] = m.d1;
    j["std_error_8bit"] = m.stdError8bit;
}

// (key, value) pairs in report order, for CSV and the difference object.
std::vector<std::pair<const char*, double>> metricFields(const StereoMetrics& m) {
    return {{"gt_pixels", double(m.gtPixels)},
            {"estimated_pixels", double(m.estimatedPixels)},
            {"coverage", m.coverage},
            {"mean_abs_error", m.meanAbsError},
            {"mean_error", m.meanError},
            {"std_error", m.stdError},
            {"rms", m.rms},
            {"max_abs_error", m.maxAbsError},
            {"bad_0_5", m.bad[0]},
            {"bad_1", m.bad[1]},
            {"bad_2", m.bad[2]},
            {"bad_4", m.bad[3]},
            {"a50", m.accuracy[0]},
            {"a90", m.accuracy[1]},
            {"a95", m.accuracy[2]},
            {"a99", m.accuracy[3]},
            {"d1_all", m.d1},
            {"std_error_8bit", m.stdError8bit}};
}

Json datasetJson(const DatasetEvaluation& d) {
    Json j;
    j["dataset"] = d.datasetDir;
    j["matcher"] = d.matcher;
    j["width"] = d.width;
    j["height"] = d.height;
    j["frames"] = d.frames.size();
    putMetrics(j, d.total.metrics());
    if (d.nonOccluded) putMetrics(j["noc"], d.nonOccluded->metrics());
    Json perFrame = Json::array();
    for (const FrameMetrics& f : d.frames) {
        Json fj;
        fj["frame"] = f.frame;
        fj["frames"] = 1;
        putMetrics(fj, f.metrics);
        perFrame.push_back(fj);
    }
    j["per_frame"] = perFrame;
    if (!d.classes.empty()) {
        Json classes = Json::object();
        for (const GroupMetrics& g : d.classes) putMetrics(classes[g.name], g.accumulator.metrics());
        j["classes"] = classes;
    }
    Json bands = Json::array();
    for (const GroupMetrics& g : d.bands) {
        Json bj;
        bj["band"] = g.name;
        bj["min_m"] = g.minMetres;
        bj["max_m"] = std::isinf(g.maxMetres) ? Json(nullptr) : Json(g.maxMetres);
        putMetrics(bj, g.accumulator.metrics());
        bands.push_back(bj);
    }
    j["distance_bands"] = bands;
    return j;
}

struct RowSpec {
    const char* label;
    double (*get)(const StereoMetrics&);
    bool fraction;
};

const RowSpec kRows[] = {
    {"pixels with ground truth", [](const StereoMetrics& m) { return double(m.gtPixels); }, false},
    {"coverage (estimated / ground truth)", [](const StereoMetrics& m) { return m.coverage; }, true},
    {"mean \\|e\\| (px)", [](const StereoMetrics& m) { return m.meanAbsError; }, false},
    {"mean e (px)", [](const StereoMetrics& m) { return m.meanError; }, false},
    {"std e (px)", [](const StereoMetrics& m) { return m.stdError; }, false},
    {"RMS (px)", [](const StereoMetrics& m) { return m.rms; }, false},
    {"std of 8-bit difference image", [](const StereoMetrics& m) { return m.stdError8bit; }, false},
    {"bad-0.5", [](const StereoMetrics& m) { return m.bad[0]; }, true},
    {"bad-1", [](const StereoMetrics& m) { return m.bad[1]; }, true},
    {"bad-2", [](const StereoMetrics& m) { return m.bad[2]; }, true},
    {"bad-4", [](const StereoMetrics& m) { return m.bad[3]; }, true},
    {"A50 (px)", [](const StereoMetrics& m) { return m.accuracy[0]; }, false},
    {"A90 (px)", [](const StereoMetrics& m) { return m.accuracy[1]; }, false},
    {"A95 (px)", [](const StereoMetrics& m) { return m.accuracy[2]; }, false},
    {"A99 (px)", [](const StereoMetrics& m) { return m.accuracy[3]; }, false},
    {"KITTI D1-all", [](const StereoMetrics& m) { return m.d1; }, true},
};

std::string cell(const RowSpec& row, const StereoMetrics& m) {
    double v = row.get(m);
    if (&row == &kRows[0]) return fixed(v, 0);
    return row.fraction ? percent(v) : fixed(v, 3);
}

std::string differenceCell(const RowSpec& row, const StereoMetrics& a, const StereoMetrics& b) {
    double d = row.get(a) - row.get(b);
    if (&row == &kRows[0]) return signedFixed(d, 0);
    if (!std::isfinite(d)) return "n/a";
    return row.fraction ? signedFixed(100.0 * d, 2) + " pt" : signedFixed(d, 3);
}

std::string groupTable(const std::vector<GroupMetrics>& groups) {
    std::string md = "| | pixels | coverage | mean \\|e\\| | mean e | std e | bad-2 | A90 | D1-all |\n"
                     "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const GroupMetrics& g : groups) {
        StereoMetrics m = g.accumulator.metrics();
        if (m.gtPixels == 0) continue;
        md += "| " + g.name + " | " + std::to_string(m.gtPixels) + " | " + percent(m.coverage) + " | " +
              fixed(m.meanAbsError, 3) + " | " + fixed(m.meanError, 3) + " | " + fixed(m.stdError, 3) + " | " +
              percent(m.bad[2]) + " | " + fixed(m.accuracy[1], 3) + " | " + percent(m.d1) + " |\n";
    }
    return md;
}

std::string markdownPictures(const std::string& prefix, uint32_t frame) {
    const std::string base = prefix + "frames/" + frameName(frame);
    return "| estimate | ground truth | signed difference (127 = 0 px) |\n|---|---|---|\n| ![](" + base +
           "_estimate.png) | ![](" + base + "_truth.png) | ![](" + base + "_difference.png) |\n";
}

// The metric rows of `main`, beside `against`'s and their difference when given.
std::string metricsTable(const EvaluationReport& report, const StereoMetrics& main, const StereoMetrics* against) {
    std::string md = against ? "| metric | " + report.main.datasetDir + " | " + report.against->datasetDir +
                                   " | difference |\n|---|---:|---:|---:|\n"
                             : "| metric | value |\n|---|---:|\n";
    for (const RowSpec& row : kRows) {
        md += std::string("| ") + row.label + " | " + cell(row, main);
        if (against) md += " | " + cell(row, *against) + " | " + differenceCell(row, main, *against);
        md += " |\n";
    }
    return md;
}

} // namespace

std::string metricsJson(const EvaluationReport& report) {
    Json j = datasetJson(report.main);
    if (report.against) {
        j["against"] = datasetJson(*report.against);
        Json difference;
        const auto a = metricFields(report.main.total.metrics()), b = metricFields(report.against->total.metrics());
        difference["frames"] = int64_t(report.main.frames.size()) - int64_t(report.against->frames.size());
        for (size_t i = 0; i < a.size(); ++i) {
            const std::string key = a[i].first;
            if (key == "gt_pixels" || key == "estimated_pixels") // counts stay integers
                difference[key] = int64_t(a[i].second) - int64_t(b[i].second);
            else
                difference[key] = a[i].second - b[i].second;
        }
        j["difference"] = difference;
    }
    return j.dump(2) + "\n";
}

std::string metricsCsv(const EvaluationReport& report) {
    std::string csv = "dataset,frame";
    for (const auto& field : metricFields(StereoMetrics{})) csv += std::string(",") + field.first;
    csv += "\n";
    auto rows = [&](const DatasetEvaluation& d, const char* label) {
        auto line = [&](const std::string& frame, const StereoMetrics& m) {
            csv += std::string(label) + "," + frame;
            for (const auto& field : metricFields(m)) csv += "," + csvNumber(field.second);
            csv += "\n";
        };
        for (const FrameMetrics& f : d.frames) line(frameName(f.frame), f.metrics);
        line("all", d.total.metrics());
        if (d.nonOccluded) line("noc", d.nonOccluded->metrics());
    };
    rows(report.main, "main");
    if (report.against) rows(*report.against, "against");
    return csv;
}

std::string reportMarkdown(const EvaluationReport& report) {
    const DatasetEvaluation& m = report.main;
    const StereoMetrics mt = m.total.metrics();
    std::string md = "# Stereo evaluation of " + m.datasetDir + "\n\n";
    md += "- Matcher: " + m.matcher + "\n";
    md += "- " + std::to_string(m.frames.size()) + " frames of " + std::to_string(m.width) + "x" +
          std::to_string(m.height) +
          " px; errors e = estimate - ground truth over pixels with both (see "
          "docs/evaluation.md); metrics pooled over all pixels of all frames.\n";
    if (report.against) {
        const DatasetEvaluation& a = *report.against;
        md += "- Against: " + a.datasetDir + " (" + std::to_string(a.frames.size()) + " frames; " + a.matcher + ")\n";
    }
    md += "\n## Overall\n\n";
    const StereoMetrics at = report.against ? report.against->total.metrics() : StereoMetrics{};
    md += metricsTable(report, mt, report.against ? &at : nullptr);
    if (m.nonOccluded) {
        const bool both = report.against && report.against->nonOccluded;
        const StereoMetrics an = both ? report.against->nonOccluded->metrics() : StereoMetrics{};
        md += "\n## Non-occluded pixels (noc)\n\nPixels whose match the other camera sees (occlusion/ masks); the "
              "table above is all pixels with ground truth.\n\n" +
              metricsTable(report, m.nonOccluded->metrics(), both ? &an : nullptr);
    }
    auto groups = [&](const DatasetEvaluation& d, const std::string& suffix) {
        if (!d.classes.empty()) md += "\n## By semantic class" + suffix + "\n\n" + groupTable(d.classes);
        md += "\n## By distance (ground-truth depth)" + suffix + "\n\n" + groupTable(d.bands);
    };
    groups(m, "");
    if (report.against) groups(*report.against, " — " + report.against->datasetDir);

    md += "\n## Error histograms\n\n![signed error histogram](error_histogram.png)\n";
    if (!m.classes.empty()) md += "\n![signed error histogram by class](error_histogram_classes.png)\n";

    auto perFrame = [&](const DatasetEvaluation& d, const std::string& suffix) {
        md += "\n## Per frame" + suffix +
              "\n\n| frame | coverage | mean \\|e\\| | mean e | std e | RMS | bad-1 | bad-2 | D1-all |\n"
              "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for (const FrameMetrics& f : d.frames) {
            const StereoMetrics& s = f.metrics;
            md += "| " + frameName(f.frame) + " | " + percent(s.coverage) + " | " + fixed(s.meanAbsError, 3) + " | " +
                  fixed(s.meanError, 3) + " | " + fixed(s.stdError, 3) + " | " + fixed(s.rms, 3) + " | " +
                  percent(s.bad[1]) + " | " + percent(s.bad[2]) + " | " + percent(s.d1) + " |\n";
        }
    };
    perFrame(m, "");
    if (report.against) perFrame(*report.against, " — " + report.against->datasetDir);

    if (!m.frames.empty() && fs::exists(report.outDir + "/frames/" + frameName(m.frames[0].frame) + "_estimate.png")) {
        md += "\n## Frame " + frameName(m.frames[0].frame) +
              "\n\nDisparity colour scale: turbo, shared by estimate and ground truth; black = no value. "
              "All frames' pictures are in frames/.\n\n" +
              markdownPictures("", m.frames[0].frame);
        if (report.against && !report.against->frames.empty())
            md += "\n" + report.against->datasetDir + ":\n\n" +
                  markdownPictures("against/", report.against->frames[0].frame);
    }
    return md;
}

void writeReport(const EvaluationReport& report) {
    // Legend labels: the datasets' folder names, unless they are the same.
    auto folderName = [](const std::string& dir) {
        fs::path p = fs::path(dir).lexically_normal();
        return (p.has_filename() ? p.filename() : p.parent_path().filename()).string();
    };
    std::string mainLabel = folderName(report.main.datasetDir);
    std::string againstLabel = report.against ? folderName(report.against->datasetDir) : "against";
    if (mainLabel.empty() || mainLabel == againstLabel) mainLabel = "main", againstLabel = "against";
    std::vector<Curve> curves = {{mainLabel, cv::Scalar(200, 90, 20), &report.main.total}};
    if (report.against) curves.push_back({againstLabel, cv::Scalar(30, 30, 220), &report.against->total});
    plotHistograms(report.outDir + "/error_histogram.png", "Signed disparity error, all pixels", curves);
    if (!report.main.classes.empty()) {
        const cv::Scalar colours[kClassGroups.size()] = {
            {40, 160, 40}, {40, 110, 170}, {180, 60, 180}, {120, 120, 120}};
        std::vector<Curve> classCurves;
        for (size_t c = 0; c < report.main.classes.size(); ++c)
            if (report.main.classes[c].accumulator.estimatedPixels() > 0)
                classCurves.push_back({report.main.classes[c].name, colours[c], &report.main.classes[c].accumulator});
        plotHistograms(report.outDir + "/error_histogram_classes.png", "Signed disparity error by semantic class",
                       classCurves);
    }
    writeTextAtomically(report.outDir + "/metrics.json", metricsJson(report));
    writeTextAtomically(report.outDir + "/metrics.csv", metricsCsv(report));
    writeTextAtomically(report.outDir + "/report.md", reportMarkdown(report));
}

} // namespace sward

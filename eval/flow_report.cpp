#include "eval/flow_report.h"

#include "common/atomic_file.h"
#include "dataset/naming.h"
#include "eval/number_format.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

namespace sward {

namespace {

using Json = nlohmann::ordered_json;

// (key, value) pairs in report order: the JSON keys and the CSV columns.
std::vector<std::pair<const char*, double>> metricFields(const FlowMetrics& m) {
    return {{"gt_pixels", double(m.gtPixels)},
            {"estimated_pixels", double(m.estimatedPixels)},
            {"coverage", m.coverage},
            {"mean_flow", m.meanTruthMagnitude},
            {"epe", m.epe},
            {"rms_epe", m.rmsEpe},
            {"max_epe", m.maxEpe},
            {"bad_1", m.bad[0]},
            {"bad_3", m.bad[1]},
            {"fl", m.fl}};
}

// A metrics object; NaN (nothing to measure) becomes null.
Json metricsObject(const FlowMetrics& m) {
    Json j;
    j["gt_pixels"] = m.gtPixels;
    j["estimated_pixels"] = m.estimatedPixels;
    for (const auto& [key, value] : metricFields(m))
        if (std::string_view(key) != "gt_pixels" && std::string_view(key) != "estimated_pixels")
            j[key] = std::isfinite(value) ? Json(value) : Json(nullptr);
    return j;
}

// Adds "all" and, when the dataset has masks, "noc" to `j`.
void putRegions(Json& j, const FlowEvaluation& e, const FlowMetrics& all, const FlowMetrics& noc) {
    j["all"] = metricsObject(all);
    if (e.masks) j["noc"] = metricsObject(noc);
}

void putRegions(Json& j, const FlowEvaluation& e, const FlowErrors& errors) {
    putRegions(j, e, errors.all.metrics(), errors.noc.metrics());
}

std::string groupTable(const FlowEvaluation& e, const std::vector<FlowGroup>& groups, const char* what) {
    std::string md = std::string("| ") + what + " | pixels | mean \\|flow\\| | coverage | EPE all | Fl-all |" +
                     (e.masks ? " noc pixels | EPE noc | Fl-noc |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n"
                              : "\n|---|---:|---:|---:|---:|---:|\n");
    for (const FlowGroup& g : groups) {
        const FlowMetrics all = g.errors.all.metrics(), noc = g.errors.noc.metrics();
        if (all.gtPixels == 0) continue;
        md += "| " + g.name + " | " + std::to_string(all.gtPixels) + " | " + fixed(all.meanTruthMagnitude, 3) + " | " +
              percent(all.coverage) + " | " + fixed(all.epe, 3) + " | " + percent(all.fl) + " |";
        if (e.masks)
            md += " " + std::to_string(noc.gtPixels) + " | " + fixed(noc.epe, 3) + " | " + percent(noc.fl) + " |";
        md += "\n";
    }
    return md;
}

std::string overallTable(const FlowEvaluation& e) {
    const FlowMetrics all = e.total.all.metrics(), noc = e.total.noc.metrics();
    struct Row {
        const char* label;
        double (*get)(const FlowMetrics&);
        bool fraction;
    };
    const Row rows[] = {
        {"pixels with ground truth", [](const FlowMetrics& m) { return double(m.gtPixels); }, false},
        {"coverage (estimated / ground truth)", [](const FlowMetrics& m) { return m.coverage; }, true},
        {"mean \\|true flow\\| (px)", [](const FlowMetrics& m) { return m.meanTruthMagnitude; }, false},
        {"EPE (px)", [](const FlowMetrics& m) { return m.epe; }, false},
        {"RMS EPE (px)", [](const FlowMetrics& m) { return m.rmsEpe; }, false},
        {"max EPE (px)", [](const FlowMetrics& m) { return m.maxEpe; }, false},
        {"EPE > 1 px", [](const FlowMetrics& m) { return m.bad[0]; }, true},
        {"EPE > 3 px", [](const FlowMetrics& m) { return m.bad[1]; }, true},
        {"KITTI Fl", [](const FlowMetrics& m) { return m.fl; }, true},
    };
    std::string md = e.masks ? "| metric | all | noc |\n|---|---:|---:|\n" : "| metric | all |\n|---|---:|\n";
    for (const Row& row : rows) {
        auto cell = [&](const FlowMetrics& m) {
            return &row == &rows[0] ? fixed(row.get(m), 0) : row.fraction ? percent(row.get(m)) : fixed(row.get(m), 3);
        };
        md += std::string("| ") + row.label + " | " + cell(all) + (e.masks ? " | " + cell(noc) : "") + " |\n";
    }
    return md;
}

std::string perFrameTable(const FlowEvaluation& e) {
    std::string md =
        std::string("| frame | mean \\|flow\\| | coverage | EPE all | Fl-all |") +
        (e.masks ? " EPE noc | Fl-noc |\n|---|---:|---:|---:|---:|---:|---:|\n" : "\n|---|---:|---:|---:|---:|\n");
    for (const FlowFrameMetrics& f : e.frames) {
        md += "| " + frameName(f.frame) + " | " + fixed(f.all.meanTruthMagnitude, 3) + " | " + percent(f.all.coverage) +
              " | " + fixed(f.all.epe, 3) + " | " + percent(f.all.fl) + " |";
        if (e.masks) md += " " + fixed(f.noc.epe, 3) + " | " + percent(f.noc.fl) + " |";
        md += "\n";
    }
    return md;
}

} // namespace

std::string flowMetricsJson(const FlowEvaluation& e) {
    Json j;
    j["dataset"] = e.datasetDir;
    j["method"] = e.method;
    j["width"] = e.width;
    j["height"] = e.height;
    j["frames"] = e.frames.size();
    j["masks"] = e.masks;
    putRegions(j, e, e.total);
    Json perFrame = Json::array();
    for (const FlowFrameMetrics& f : e.frames) {
        Json fj;
        fj["frame"] = f.frame;
        putRegions(fj, e, f.all, f.noc);
        perFrame.push_back(fj);
    }
    j["per_frame"] = perFrame;
    if (!e.classes.empty()) {
        Json classes = Json::object();
        for (const FlowGroup& g : e.classes) putRegions(classes[g.name], e, g.errors);
        j["classes"] = classes;
    }
    if (!e.bands.empty()) {
        Json bands = Json::array();
        for (const FlowGroup& g : e.bands) {
            Json bj;
            bj["band"] = g.name;
            bj["min_m"] = g.minMetres;
            bj["max_m"] = std::isinf(g.maxMetres) ? Json(nullptr) : Json(g.maxMetres);
            putRegions(bj, e, g.errors);
            bands.push_back(bj);
        }
        j["distance_bands"] = bands;
    }
    return j.dump(2) + "\n";
}

std::string flowMetricsCsv(const FlowEvaluation& e) {
    std::string csv = "frame,region";
    for (const auto& field : metricFields(FlowMetrics{})) csv += std::string(",") + field.first;
    csv += "\n";
    auto line = [&](const std::string& frame, const char* region, const FlowMetrics& m) {
        csv += frame + "," + region;
        for (const auto& field : metricFields(m)) csv += "," + csvNumber(field.second);
        csv += "\n";
    };
    auto rows = [&](const std::string& frame, const FlowMetrics& all, const FlowMetrics& noc) {
        line(frame, "all", all);
        if (e.masks) line(frame, "noc", noc);
    };
    for (const FlowFrameMetrics& f : e.frames) rows(frameName(f.frame), f.all, f.noc);
    rows("total", e.total.all.metrics(), e.total.noc.metrics());
    return csv;
}

std::string flowReportMarkdown(const FlowEvaluation& e) {
    std::string md = "# Optical-flow evaluation of " + e.datasetDir + "\n\n";
    md += "- Method: " + e.method + "\n";
    md += "- " + std::to_string(e.frames.size()) + " frames of " + std::to_string(e.width) + "x" +
          std::to_string(e.height) +
          " px, forward flow of each frame to the next; EPE = \\|estimate - truth\\| over pixels with both, KITTI "
          "Fl = share of pixels with EPE > 3 px and > 5 % of \\|truth\\| (docs/evaluation.md); pooled over all pixels "
          "of all frames.\n";
    md += e.masks ? "- all: every pixel with ground truth (occluded ones too); noc: pixels visible in both frames "
                    "(flow_forward_mask 255).\n"
                  : "- all: every pixel with ground truth; the dataset has no flow_forward_mask/, so no noc figures.\n";
    md += "\n## Overall\n\n" + overallTable(e);
    if (!e.classes.empty()) md += "\n## By semantic class\n\n" + groupTable(e, e.classes, "class");
    if (!e.bands.empty()) md += "\n## By distance (depth of the source pixel)\n\n" + groupTable(e, e.bands, "band");
    md += "\n## Per frame\n\n" + perFrameTable(e);
    if (!e.frames.empty()) {
        const std::string base = "frames/" + frameName(e.frames[0].frame);
        if (fs::exists(e.outDir + "/" + base + "_estimate.png"))
            md += "\n## Frame " + frameName(e.frames[0].frame) +
                  "\n\nMiddlebury colour wheel (hue = direction, saturation = speed, scaled to the frame's largest "
                  "true motion); EPE map: turbo from 0 to 8 px; black = no value. All frames' pictures are in "
                  "frames/.\n\n| estimate | ground truth | end-point error |\n|---|---|---|\n| ![](" +
                  base + "_estimate.png) | ![](" + base + "_truth.png) | ![](" + base + "_epe.png) |\n";
    }
    return md;
}

void writeFlowReport(const FlowEvaluation& evaluation) {
    writeTextAtomically(evaluation.outDir + "/metrics.json", flowMetricsJson(evaluation));
    writeTextAtomically(evaluation.outDir + "/metrics.csv", flowMetricsCsv(evaluation));
    writeTextAtomically(evaluation.outDir + "/report.md", flowReportMarkdown(evaluation));
}

} // namespace sward

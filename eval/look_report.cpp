#include "eval/look_report.h"

#include "common/atomic_file.h"
#include "eval/number_format.h"

#include <nlohmann/json.hpp>

#include <cmath>

namespace sward {

namespace {

using Json = nlohmann::ordered_json;

Json number(double v) {
    return std::isfinite(v) ? Json(v) : Json(nullptr);
}

Json statisticsObject(const LookStatistics& s) {
    Json j = Json::object();
    for (const LookField& f : lookFields(s))
        j[f.key] = f.compared ? number(f.value) : Json(uint64_t(f.value)); // counts are whole numbers
    return j;
}

Json imagesArray(const std::vector<LookImageResult>& images, const char* nameKey, bool frames) {
    Json list = Json::array();
    for (const LookImageResult& image : images) {
        Json j;
        j[nameKey] = image.name;
        j["width"] = image.width;
        j["height"] = image.height;
        if (frames) j["smooth_turf_share"] = number(image.smoothTurfShare);
        Json regions = Json::object();
        for (const auto& [name, stats] : image.regions) regions[name] = statisticsObject(stats);
        j["regions"] = regions;
        list.push_back(j);
    }
    return list;
}

Json summaryObject(const LookSummaries& summaries, const std::vector<std::string>& order) {
    Json j = Json::object();
    for (const std::string& region : order) {
        auto it = summaries.find(region);
        if (it == summaries.end()) continue;
        Json r;
        r["images"] = it->second.images;
        for (size_t i = 0; i < it->second.keys.size(); ++i) r[it->second.keys[i]] = number(it->second.median[i]);
        j[region] = r;
    }
    return j;
}

// The compared fields' indices (the same in every summary: lookFields' order).
std::vector<size_t> comparedFields() {
    std::vector<size_t> indices;
    const std::vector<LookField> fields = lookFields(LookStatistics{});
    for (size_t i = 0; i < fields.size(); ++i)
        if (fields[i].compared) indices.push_back(i);
    return indices;
}

Json gapObject(const LookResult& r) {
    Json j = Json::object();
    const std::vector<LookField> fields = lookFields(LookStatistics{});
    for (const std::string& region : r.regionOrder) {
        auto s = r.sward.find(region), real = r.real.find(region);
        if (s == r.sward.end() || real == r.real.end()) continue;
        Json g;
        for (size_t i : comparedFields()) g[fields[i].key] = number(lookGap(s->second, real->second, i));
        j[region] = g;
    }
    return j;
}

// How many decimals a statistic reads best with.
std::string cell(const char* key, double v) {
    const std::string k = key;
    if (k.ends_with("_per_mp") || k == "pixels" || k.ends_with("_pixels") || k.ends_with("_windows") ||
        k.ends_with("_blocks") || k == "hue_std_deg")
        return fixed(v, k == "hue_std_deg" ? 1 : 0);
    if (k.starts_with("spectrum_slope") || k.ends_with("kurtosis")) return fixed(v, 2);
    return fixed(v, 4);
}

std::string summaryTable(const LookResult& r, const std::string& region) {
    const LookSummary& s = r.sward.at(region);
    auto real = r.real.find(region);
    const bool compare = real != r.real.end();
    std::string md = compare
                         ? "| statistic | sward median | real median | real IQR | gap |\n|---|---:|---:|---:|---:|\n"
                         : "| statistic | sward median |\n|---|---:|\n";
    const std::vector<LookField> fields = lookFields(LookStatistics{});
    for (size_t i = 0; i < fields.size(); ++i) {
        md += std::string("| ") + fields[i].key + " | " + cell(fields[i].key, s.median[i]);
        if (compare)
            md += " | " + cell(fields[i].key, real->second.median[i]) + " | " +
                  cell(fields[i].key, real->second.q1[i]) + " - " + cell(fields[i].key, real->second.q3[i]) + " | " +
                  (fields[i].compared ? signedFixed(lookGap(s, real->second, i), 2) : "");
        md += " |\n";
    }
    return md;
}

} // namespace

std::string lookJson(const LookResult& r) {
    Json j;
    j["dataset"] = r.datasetDir;
    j["reference"] = r.referenceDir.empty() ? Json(nullptr) : Json(r.referenceDir);
    j["frames"] = imagesArray(r.frames, "frame", true);
    j["smooth_turf_share"] = number(r.smoothTurfShare);
    j["summary"] = summaryObject(r.sward, r.regionOrder);
    if (!r.referenceDir.empty()) {
        j["reference_images"] = imagesArray(r.reference, "file", false);
        j["reference_summary"] = summaryObject(r.real, r.regionOrder);
        j["gap"] = gapObject(r);
    }
    return j.dump(2) + "\n";
}

std::string lookCsv(const LookResult& r) {
    std::string csv = "source,image,region";
    for (const LookField& f : lookFields(LookStatistics{})) csv += std::string(",") + f.key;
    csv += "\n";
    auto rows = [&](const char* source, const std::vector<LookImageResult>& images) {
        for (const LookImageResult& image : images)
            for (const auto& [region, stats] : image.regions) {
                csv += std::string(source) + "," + image.name + "," + region;
                for (const LookField& f : lookFields(stats)) csv += "," + csvNumber(f.value);
                csv += "\n";
            }
    };
    rows("sward", r.frames);
    rows("real", r.reference);
    return csv;
}

std::string lookMarkdown(const LookResult& r, bool pictures) {
    std::string md = "# Realism statistics of " + r.datasetDir + "\n\n";
    md += "- " + std::to_string(r.frames.size()) + " frames of the 8-bit preview";
    md += r.referenceDir.empty() ? "; no reference folder.\n"
                                 : "; " + std::to_string(r.reference.size()) + " real images of " + r.referenceDir +
                                       ".\n- gap = (sward median - real median) / real IQR (the real std where the "
                                       "IQR is 0).\n";
    md += "- Smooth turf (turf pixels failing the sharp-texture test, share of the non-sky pixels; median over the "
          "frames): " +
          percent(r.smoothTurfShare) + ".\n";
    md += "- Medians over the images holding the region; every statistic is defined in docs/evaluation.md "
          "(\"Realism statistics\"); per-frame values in look.json and look.csv.\n";
    const std::vector<std::string> drawn = pictures ? lookPictureRegions(r) : std::vector<std::string>();
    for (const std::string& region : r.regionOrder) {
        if (!r.sward.contains(region)) continue;
        md += "\n## Region " + region + "\n\n" + summaryTable(r, region);
        if (std::find(drawn.begin(), drawn.end(), region) != drawn.end())
            md += "\n![grey, saturation and spectrum of " + region + "](look_" + region + ".png)\n";
    }
    return md;
}

void writeLookReport(const LookResult& r, const std::string& outDir, bool pictures) {
    writeTextAtomically(outDir + "/look.json", lookJson(r));
    writeTextAtomically(outDir + "/look.csv", lookCsv(r));
    writeTextAtomically(outDir + "/report.md", lookMarkdown(r, pictures));
    if (pictures) writeLookPictures(r, outDir);
}

} // namespace sward

#include "eval/look_regions.h"

#include "common/error.h"
#include "common/input_file.h"
#include "dataset/naming.h"

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <set>
#include <string_view>

namespace fs = std::filesystem;

namespace sward {

namespace {

enum RegionBits : uint8_t { kInAll = 1, kInVegetation = 2, kInSoil = 4, kInTurf = 8, kInSurface = 16 };

// What each semantic id counts in (dataset/naming.h's table).
std::array<uint8_t, 256> regionTable() {
    std::array<uint8_t, 256> table{};
    for (const SemanticClass& c : semanticClasses()) {
        const std::string_view name = c.name, group = c.group;
        uint8_t bits = 0;
        if (group != "sky") bits |= kInAll;
        if (group == "vegetation" || name == "turf") bits |= kInVegetation;
        if (name == "ground" || name == "track") bits |= kInSoil;
        if (name == "turf") bits |= kInTurf;
        if (group != "sky" && group != "object") bits |= kInSurface;
        table[c.id] = bits;
    }
    return table;
}

std::string lower(std::string text) {
    for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

bool isImageName(const std::string& name) {
    const std::string l = lower(name);
    for (const char* ext : {".png", ".jpg", ".jpeg"})
        if (l.size() > std::string_view(ext).size() && l.ends_with(ext)) return true;
    return false;
}

// `dir`/`name` when it stays inside `dir` (canonical paths, so a link out of the folder is refused too).
std::string insideFolder(const fs::path& canonicalDir, const std::string& name, const std::string& what) {
    require(!name.empty() && name.find('/') == std::string::npos && name != "." && name != "..",
            canonicalDir.string() + "/" + kLookRegionsFile + ": " + what + " '" + name +
                "' is not a file name inside the reference folder");
    std::error_code ec;
    const fs::path real = fs::weakly_canonical(canonicalDir / name, ec);
    const auto [end, _] = std::mismatch(canonicalDir.begin(), canonicalDir.end(), real.begin(), real.end());
    require(!ec && end == canonicalDir.end(),
            (canonicalDir / name).string() + ": the " + what + " leads out of the reference folder");
    return (canonicalDir / name).string();
}

cv::Mat decode(const std::string& path, int flags, const std::string& what) {
    const std::vector<unsigned char> bytes = readInputBytes(path, what);
    cv::Mat image = cv::imdecode(bytes, flags);
    require(!image.empty() && image.depth() == CV_8U, path + ": cannot decode the " + what + " as an 8-bit image");
    return image;
}

cv::Mat rectanglesMask(const nlohmann::json& list, cv::Size size, const std::string& where) {
    cv::Mat mask = cv::Mat::zeros(size, CV_8U);
    for (const nlohmann::json& r : list) {
        require(r.is_array() && r.size() == 4 &&
                    std::all_of(r.begin(), r.end(), [](auto& v) { return v.is_number_integer(); }),
                where + ": a crop rectangle is [x, y, w, h] in whole pixels");
        const cv::Rect rect(r[0].get<int>(), r[1].get<int>(), r[2].get<int>(), r[3].get<int>());
        require(rect.width > 0 && rect.height > 0, where + ": a crop rectangle has a positive width and height");
        mask(rect & cv::Rect(cv::Point(0, 0), size)).setTo(255);
    }
    return mask;
}

std::vector<LookRegion> regionsOf(const fs::path& dir, const std::string& file, const nlohmann::json& entry,
                                  cv::Size size) {
    const std::string where = (dir / kLookRegionsFile).string() + " '" + file + "'";
    require(entry.is_object(), where + ": expected an object of regions");
    std::vector<LookRegion> regions;
    for (const auto& [name, value] : entry.items()) {
        if (value.is_string()) {
            const std::string path = insideFolder(dir, value.get<std::string>(), "region mask");
            cv::Mat mask = decode(path, cv::IMREAD_GRAYSCALE, "region mask");
            require(mask.size() == size, path + ": the region mask is " + std::to_string(mask.cols) + "x" +
                                             std::to_string(mask.rows) + ", its image " + std::to_string(size.width) +
                                             "x" + std::to_string(size.height));
            regions.push_back({name, mask != 0});
        } else {
            require(value.is_array(), where + " region '" + name + "': expected crop rectangles or a mask file name");
            regions.push_back({name, rectanglesMask(value, size, where + " region '" + name + "'")});
        }
    }
    return regions;
}

} // namespace

std::vector<LookRegion> swardRegions(const cv::Mat& semantic) {
    static const std::array<uint8_t, 256> table = regionTable();
    std::vector<LookRegion> regions;
    for (const char* name : kSwardRegionNames) regions.push_back({name, cv::Mat::zeros(semantic.size(), CV_8U)});
    int top = -1;
    for (int y = 0; y < semantic.rows; ++y)
        for (int x = 0; x < semantic.cols; ++x) {
            const uint8_t bits = table[semantic.at<uint8_t>(y, x)];
            for (int r = 0; r < 4; ++r)
                if (bits & (1 << r)) regions[size_t(r)].mask.at<uint8_t>(y, x) = 255;
            if ((bits & kInSurface) && top < 0) top = y;
        }
    if (top < 0) return regions;
    const int end = std::min(semantic.rows, top + int(std::ceil(kLookFarBandFraction * semantic.rows)));
    for (int y = top; y < end; ++y)
        for (int x = 0; x < semantic.cols; ++x)
            if (table[semantic.at<uint8_t>(y, x)] & kInSurface) regions[4].mask.at<uint8_t>(y, x) = 255;
    return regions;
}

std::vector<ReferenceImage> readReferenceImages(const std::string& dir) {
    std::error_code ec;
    require(fs::is_directory(dir, ec), "reference folder '" + dir + "' does not exist");
    const fs::path canonical = fs::canonical(dir, ec);
    require(!ec, "reference folder '" + dir + "': " + ec.message());
    std::vector<std::string> names;
    for (const fs::directory_entry& e : fs::directory_iterator(canonical))
        if (isImageName(e.path().filename().string())) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    require(!names.empty(), "reference folder '" + dir + "' holds no image (*.png, *.jpg, *.jpeg)");
    nlohmann::json regions = nlohmann::json::object();
    const fs::path regionsPath = canonical / kLookRegionsFile;
    if (fs::exists(regionsPath, ec)) {
        try {
            regions = nlohmann::json::parse(readInputFile(regionsPath.string(), "regions file"));
        } catch (const nlohmann::json::exception& e) {
            throw Error(regionsPath.string() + ": not valid JSON (" + e.what() + ")");
        }
        require(regions.is_object(), regionsPath.string() + ": expected an object keyed by image file name");
        const std::set<std::string> known(names.begin(), names.end());
        for (const auto& [file, _] : regions.items())
            require(known.contains(file), regionsPath.string() + ": '" + file + "' is no image of the folder");
    }
    std::vector<ReferenceImage> images;
    for (const std::string& name : names) {
        ReferenceImage image{
            name, decode(insideFolder(canonical, name, "image"), cv::IMREAD_COLOR, "reference image"), {}};
        if (regions.contains(name))
            image.regions = regionsOf(canonical, name, regions[name], image.bgr.size());
        else
            image.regions.push_back({"all", cv::Mat(image.bgr.size(), CV_8U, cv::Scalar(255))});
        images.push_back(std::move(image));
    }
    return images;
}

} // namespace sward

#include "io/disparity_files.h"
#include "io/image_files.h"
#include "io/image_io.h"

#include "common/error.h"
#include "common/input_file.h"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <sstream>

namespace sward {

namespace {

void requireSize(const std::string& path, uint32_t width, uint32_t height, size_t count) {
    require(width > 0 && height > 0, path + ": cannot write an empty " + std::to_string(width) + "x" +
                                         std::to_string(height) + " disparity map");
    require(count == size_t(width) * height, path + ": disparity has " + std::to_string(count) + " values, expected " +
                                                 std::to_string(width) + "x" + std::to_string(height));
}

std::string readWholeFile(const std::string& path) {
    std::error_code ec;
    require(std::filesystem::exists(path, ec), "cannot open '" + path + "': no such file");
    return readInputFile(path, "file"); // the input door: a FIFO or a device is refused without blocking
}

// Reads the next whitespace-delimited token of a PFM header; PFM allows any whitespace between fields.
std::string headerToken(const std::string& data, size_t& pos) {
    while (pos < data.size() && std::isspace(static_cast<unsigned char>(data[pos]))) ++pos;
    size_t start = pos;
    while (pos < data.size() && !std::isspace(static_cast<unsigned char>(data[pos]))) ++pos;
    return data.substr(start, pos - start);
}

std::string formatNumber(double v) {
    char buffer[64];
    auto result = std::to_chars(buffer, buffer + sizeof(buffer), v); // shortest text that reads back exactly
    return std::string(buffer, result.ptr);
}

double parseNumber(const std::string& text, const std::string& what) {
    double v = 0;
    const char* begin = text.data();
    const char* end = text.data() + text.size();
    while (begin < end && std::isspace(static_cast<unsigned char>(*begin))) ++begin;
    while (end > begin && std::isspace(static_cast<unsigned char>(end[-1]))) --end;
    auto result = std::from_chars(begin, end, v);
    require(result.ec == std::errc() && result.ptr == end && std::isfinite(v),
            what + ": '" + text + "' is not a number");
    return v;
}

uint32_t parseCount(const std::string& text, const std::string& what) {
    double v = parseNumber(text, what);
    require(v >= 0 && v <= 1e9 && v == std::floor(v), what + ": '" + text + "' is not a whole number");
    return uint32_t(v);
}

std::array<double, 9> parseMatrix(const std::string& text, const std::string& what) {
    std::string inner = text;
    size_t open = inner.find('['), close = inner.rfind(']');
    require(open != std::string::npos && close != std::string::npos && close > open,
            what + ": expected a matrix like [f 0 cx; 0 f cy; 0 0 1], got '" + text + "'");
    inner = inner.substr(open + 1, close - open - 1);
    for (char& c : inner)
        if (c == ';' || c == ',') c = ' ';
    std::istringstream in(inner);
    std::array<double, 9> m{};
    size_t n = 0;
    for (std::string token; in >> token;) {
        require(n < 9, what + ": more than 9 entries in '" + text + "'");
        m[n++] = parseNumber(token, what);
    }
    require(n == 9, what + ": expected 9 entries in '" + text + "', found " + std::to_string(n));
    return m;
}

std::string formatMatrix(const std::array<double, 9>& m) {
    std::string s = "[";
    for (int i = 0; i < 9; ++i) {
        s += formatNumber(m[i]);
        s += (i == 8) ? "]" : (i % 3 == 2) ? "; " : " ";
    }
    return s;
}

} // namespace

void writePfm(const std::string& path, uint32_t width, uint32_t height, std::span<const float> disparity) {
    std::vector<float> values(disparity.begin(), disparity.end());
    for (float& v : values)
        if (!isValidDisparity(v)) v = std::numeric_limits<float>::infinity();
    writePfmValues(path, width, height, values);
}

void writePfmValues(const std::string& path, uint32_t width, uint32_t height, std::span<const float> disparity) {
    requireSize(path, width, height, disparity.size());
    std::string header = "Pf\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1\n";
    std::string data(header.size() + disparity.size() * 4, '\0');
    std::memcpy(data.data(), header.data(), header.size());
    char* out = data.data() + header.size();
    for (uint32_t row = 0; row < height; ++row) {
        const float* src = disparity.data() + size_t(height - 1 - row) * width; // PFM stores the bottom row first
        for (uint32_t x = 0; x < width; ++x) {
            uint32_t bits = std::bit_cast<uint32_t>(src[x]);
            if constexpr (std::endian::native == std::endian::big) bits = __builtin_bswap32(bits);
            std::memcpy(out, &bits, 4);
            out += 4;
        }
    }
    writeBytesAtomically(path, data.data(), data.size());
}

DisparityMap readPfm(const std::string& path) {
    const std::string data = readWholeFile(path);
    size_t pos = 0;
    std::string magic = headerToken(data, pos);
    require(magic != "PF", path + ": colour PFM (PF) is not a disparity map; expected a one-channel 'Pf' file");
    require(magic == "Pf", path + ": not a PFM file (expected the header 'Pf')");
    std::string w = headerToken(data, pos), h = headerToken(data, pos), s = headerToken(data, pos);
    uint32_t width = parseCount(w, path + ": PFM width"), height = parseCount(h, path + ": PFM height");
    double scale = parseNumber(s, path + ": PFM scale");
    require(width > 0 && height > 0 && width <= 65536 && height <= 65536,
            path + ": PFM size " + w + "x" + h + " is out of range");
    require(scale != 0, path + ": PFM scale must not be 0");
    ++pos; // exactly one whitespace character separates the header from the raster
    const size_t count = size_t(width) * height;
    require(pos <= data.size() && data.size() - pos >= count * 4,
            path + ": PFM is truncated: " + std::to_string(width) + "x" + std::to_string(height) + " needs " +
                std::to_string(count * 4) + " bytes of data");
    const bool fileLittle = scale < 0;
    const bool swap = fileLittle != (std::endian::native == std::endian::little);
    DisparityMap map{width, height, std::vector<float>(count)};
    const char* in = data.data() + pos;
    for (uint32_t row = 0; row < height; ++row) {
        float* dst = map.values.data() + size_t(height - 1 - row) * width;
        for (uint32_t x = 0; x < width; ++x) {
            uint32_t bits;
            std::memcpy(&bits, in, 4);
            in += 4;
            if (swap) bits = __builtin_bswap32(bits);
            float v = std::bit_cast<float>(bits);
            dst[x] = isValidDisparity(v) ? v : 0.0f;
        }
    }
    return map;
}

void writeKittiPng(const std::string& path, uint32_t width, uint32_t height, std::span<const float> disparity) {
    requireSize(path, width, height, disparity.size());
    std::vector<uint16_t> samples(disparity.size());
    for (size_t i = 0; i < samples.size(); ++i) {
        const float d = disparity[i];
        const double scaled = isValidDisparity(d) ? std::round(double(d) * 256.0) : 0.0;
        // A tiny positive disparity rounds to 0, which KITTI reads as "invalid": the honest outcome.
        samples[i] = scaled > 65535.0 ? 0 : uint16_t(scaled);
    }
    writePng16(path, width, height, 1, samples);
}

DisparityMap readKittiPng(const std::string& path) {
    // Through sward's PNG reader, not cv::imread: OpenCV picks a decoder by content (a ".png" holding JPEG 2000
    // would reach OpenJPEG), and the reader checks the header against the file before anything is allocated.
    const ImageData image = loadImage(path);
    require(image.bitDepth == 16 && image.channels == 1,
            path + ": a KITTI disparity PNG must be 16-bit single-channel (found " + std::to_string(image.bitDepth) +
                "-bit, " + std::to_string(image.channels) + " channel(s))");
    DisparityMap map{image.width, image.height, std::vector<float>(image.samples.size())};
    // Samples are v / 65535 in float; v is recovered exactly by rounding (24-bit mantissa, 16-bit values).
    for (size_t i = 0; i < image.samples.size(); ++i)
        map.values[i] = float(std::lround(image.samples[i] * 65535.0f)) / 256.0f;
    return map;
}

DisparityMap readDisparity(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == "pfm") return readPfm(path);
    if (ext == "png") return readKittiPng(path);
    throw Error(path + ": unknown disparity format '" + (ext.empty() ? "" : "." + ext) + "' (expected .pfm or KITTI .png)");
}

void writeMiddleburyCalib(const std::string& path, const StereoCalib& calib) {
    std::string text;
    text += "cam0=" + formatMatrix(calib.cam0) + "\n";
    text += "cam1=" + formatMatrix(calib.cam1) + "\n";
    text += "doffs=" + formatNumber(calib.doffs) + "\n";
    text += "baseline=" + formatNumber(calib.baselineMm) + "\n";
    text += "width=" + std::to_string(calib.width) + "\n";
    text += "height=" + std::to_string(calib.height) + "\n";
    text += "ndisp=" + std::to_string(calib.ndisp) + "\n";
    text += std::string("isint=") + (calib.isint ? "1" : "0") + "\n";
    text += "vmin=" + formatNumber(calib.vmin) + "\n";
    text += "vmax=" + formatNumber(calib.vmax) + "\n";
    writeTextAtomically(path, text);
}

StereoCalib readMiddleburyCalib(const std::string& path) {
    std::istringstream in(readWholeFile(path));
    std::map<std::string, std::string> values;
    int lineNumber = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNumber;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.find_first_not_of(" \t") == std::string::npos) continue;
        size_t eq = line.find('=');
        require(eq != std::string::npos,
                path + ":" + std::to_string(lineNumber) + ": expected key=value, got '" + line + "'");
        std::string key = line.substr(0, eq);
        key.erase(0, key.find_first_not_of(" \t"));
        key.erase(key.find_last_not_of(" \t") + 1);
        values[key] = line.substr(eq + 1);
    }
    auto get = [&](const char* key, bool required) -> const std::string* {
        auto it = values.find(key);
        require(it != values.end() || !required, path + ": missing '" + key + "='");
        return it == values.end() ? nullptr : &it->second;
    };
    StereoCalib calib;
    const std::string where = path + ": ";
    calib.cam0 = parseMatrix(*get("cam0", true), where + "cam0");
    calib.cam1 = parseMatrix(*get("cam1", true), where + "cam1");
    calib.baselineMm = parseNumber(*get("baseline", true), where + "baseline");
    calib.width = parseCount(*get("width", true), where + "width");
    calib.height = parseCount(*get("height", true), where + "height");
    calib.ndisp = parseCount(*get("ndisp", true), where + "ndisp");
    if (auto* v = get("doffs", false)) calib.doffs = parseNumber(*v, where + "doffs");
    if (auto* v = get("isint", false)) calib.isint = parseCount(*v, where + "isint") != 0;
    if (auto* v = get("vmin", false)) calib.vmin = parseNumber(*v, where + "vmin");
    if (auto* v = get("vmax", false)) calib.vmax = parseNumber(*v, where + "vmax");
    require(calib.cam0[0] > 0, where + "the focal length cam0[0] must be positive");
    require(calib.baselineMm > 0, where + "baseline must be positive");
    require(calib.ndisp > 0, where + "ndisp must be positive");
    return calib;
}

} // namespace sward

#include "io/image_io.h"

#include "common/error.h"
#include "common/input_file.h"
#include "io/exr_header_check.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <stb_image.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <utility>
#include <memory>

namespace sward {

namespace {

void requireEdges(const std::string& path, uint64_t width, uint64_t height, uint32_t maxEdge = kMaxImageEdge) {
    require(width > 0 && height > 0 && width <= maxEdge && height <= maxEdge,
            "image '" + path + "' has size " + std::to_string(width) + "x" + std::to_string(height) +
                "; each edge must be 1.." + std::to_string(maxEdge) + " pixels");
}

// The decoded image's cost from its header (edges already checked, so the product cannot wrap).
void requireDecodeBudget(const std::string& path, uint64_t width, uint64_t height, uint64_t channels,
                         uint64_t bytesPerSample) {
    const uint64_t bytes = width * height * channels * bytesPerSample;
    require(bytes <= kMaxDecodedImageBytes,
            "image '" + path + "' (" + std::to_string(width) + "x" + std::to_string(height) + ", " +
                std::to_string(channels) + " channels) would take " + std::to_string(bytes >> 20) +
                " MiB decoded, over the limit of " + std::to_string(kMaxDecodedImageBytes >> 20) + " MiB");
}

// stb_image silently widens 1/2/4-bit grey images to 8 bits, so the true bit depth is read from the IHDR chunk,
// which the PNG specification requires to come first: 8-byte signature, length, "IHDR", width, height, depth, type.
struct PngHeader {
    uint32_t width, height, bitDepth, colorType;
};

PngHeader readPngHeader(const std::string& path, const std::vector<char>& bytes) {
    std::array<unsigned char, 26> b{};
    std::copy_n(bytes.begin(), std::min(bytes.size(), b.size()), b.begin()); // (an empty file has no data())
    static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    require(bytes.size() >= b.size() && std::equal(kSignature, kSignature + 8, b.begin()) &&
                std::equal(b.begin() + 12, b.begin() + 16, "IHDR"),
            "image '" + path + "' is not a valid PNG file (bad signature or header)");
    auto be32 = [&](size_t o) { return uint32_t(b[o]) << 24 | uint32_t(b[o + 1]) << 16 | b[o + 2] << 8 | b[o + 3]; };
    return {be32(16), be32(20), b[24], b[25]};
}

// The bytes of all IDAT chunks. Every chunk (length, type, data, CRC) must fit the file: stb_image grows its
// buffer to a chunk's stated length before reading it, so a 100-byte file could claim a 1 GiB chunk.
uint64_t compressedPngBytes(const std::string& path, const std::vector<char>& bytes) {
    uint64_t idat = 0;
    for (size_t at = 8; at + 8 <= bytes.size();) {
        const auto* c = reinterpret_cast<const unsigned char*>(bytes.data() + at);
        const uint64_t length = uint64_t(c[0]) << 24 | uint64_t(c[1]) << 16 | uint64_t(c[2]) << 8 | c[3];
        require(length + 12 <= bytes.size() - at, "image '" + path + "' has a PNG chunk of " +
                                                       std::to_string(length) + " bytes past the end of the file "
                                                       "(truncated or corrupt PNG)");
        if (std::memcmp(c + 4, "IDAT", 4) == 0) idat += length;
        if (std::memcmp(c + 4, "IEND", 4) == 0) break;
        at += size_t(length) + 12;
    }
    return idat;
}

// A PNG's pixels are deflate-compressed, and deflate expands at most 1032:1 (a 258-byte match in 2 bits). A header
// claiming more pixels than its IDAT chunks can hold is corrupt; refusing it up front keeps a 100-byte file from
// making the decoder allocate gigabytes before it notices the data is missing.
void requirePlausiblePngSize(const std::string& path, const PngHeader& header, uint64_t compressedBytes) {
    static constexpr uint32_t kChannels[7] = {1, 0, 3, 1, 2, 0, 4}; // by PNG colour type; 0: invalid type
    const uint32_t channels = header.colorType < 7 ? kChannels[header.colorType] : 0;
    require(channels > 0, "image '" + path + "' has invalid PNG colour type " + std::to_string(header.colorType));
    const uint64_t rowBytes = 1 + (uint64_t(header.width) * channels * header.bitDepth + 7) / 8; // + filter byte
    require(rowBytes * header.height <= compressedBytes * 1032,
            "image '" + path + "' claims " + std::to_string(header.width) + "x" + std::to_string(header.height) +
                " pixels, more than its " + std::to_string(compressedBytes) +
                " bytes of image data can hold (truncated or corrupt PNG)");
}

// Built only on failure: stbi_failure_reason() may be null, and require() evaluates its message eagerly.
std::string decodeFailure(const std::string& path) {
    const char* reason = stbi_failure_reason();
    return "cannot decode PNG '" + path + "': " + (reason ? reason : "corrupt or truncated data");
}

} // namespace

namespace {

// The header's checks, before anything is decoded: edges, bit depth, and a size its image data can hold.
PngHeader checkedPngHeader(const std::string& path, const std::vector<char>& bytes, uint32_t maxEdge) {
    PngHeader header = readPngHeader(path, bytes);
    requireEdges(path, header.width, header.height, std::min(maxEdge, kMaxImageEdge));
    const bool palette = header.colorType == 3;
    require(palette || header.bitDepth == 8 || header.bitDepth == 16,
            "image '" + path + "' has unsupported bit depth " + std::to_string(header.bitDepth) +
                " (PNG images must have 8 or 16 bits per sample)");
    requirePlausiblePngSize(path, header, compressedPngBytes(path, bytes));
    return header;
}

} // namespace

ImageData decodePng(const std::string& path, const std::vector<char>& bytes, uint32_t maxEdge) {
    const PngHeader header = checkedPngHeader(path, bytes, maxEdge);
    const bool palette = header.colorType == 3;
    // Palette images decode to RGBA at most; stb_image's copy (1 or 2 bytes a sample) lives beside the floats.
    static constexpr uint32_t kDecodedChannels[7] = {1, 0, 3, 4, 2, 0, 4};
    requireDecodeBudget(path, header.width, header.height, kDecodedChannels[header.colorType],
                        4 + (!palette && header.bitDepth == 16 ? 2 : 1));
    const auto* encoded = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int size = int(std::min<size_t>(bytes.size(), INT32_MAX));
    const bool wide = !palette && header.bitDepth == 16;

    int width = 0, height = 0, channels = 0;
    ImageData image{.bitDepth = wide ? 16u : 8u, .source = path};
    if (wide) {
        std::unique_ptr<stbi_us, void (*)(void*)> data(
            stbi_load_16_from_memory(encoded, size, &width, &height, &channels, 0), stbi_image_free);
        if (!data) throw Error(decodeFailure(path));
        image.samples.resize(size_t(width) * height * channels);
        for (size_t i = 0; i < image.samples.size(); ++i) image.samples[i] = float(data.get()[i]) / 65535.0f;
    } else {
        std::unique_ptr<stbi_uc, void (*)(void*)> data(
            stbi_load_from_memory(encoded, size, &width, &height, &channels, 0), stbi_image_free);
        if (!data) throw Error(decodeFailure(path));
        image.samples.resize(size_t(width) * height * channels);
        for (size_t i = 0; i < image.samples.size(); ++i) image.samples[i] = float(data.get()[i]) / 255.0f;
    }
    image.width = uint32_t(width);
    image.height = uint32_t(height);
    image.channels = uint32_t(channels);
    return image;
}

std::vector<unsigned char> decodePngRgba8(const std::string& path, const std::vector<char>& bytes, uint32_t maxEdge,
                                          uint32_t& width, uint32_t& height) {
    const PngHeader header = checkedPngHeader(path, bytes, maxEdge);
    std::vector<unsigned char> rgba;
    if (header.colorType != 3 && header.bitDepth == 16) {
        // Rounded from the float samples, as before: 16-bit textures keep their exact 8-bit values.
        const ImageData image = decodePng(path, bytes, maxEdge);
        rgba.resize(size_t(image.width) * image.height * 4);
        for (size_t p = 0; p < size_t(image.width) * image.height; ++p) {
            const float* s = &image.samples[p * image.channels];
            const bool colour = image.channels >= 3;
            const float rgbaf[4] = {s[0], colour ? s[1] : s[0], colour ? s[2] : s[0],
                                    image.channels == 4   ? s[3]
                                    : image.channels == 2 ? s[1]
                                                          : 1.0f};
            for (int c = 0; c < 4; ++c) rgba[4 * p + size_t(c)] = (unsigned char)std::lround(rgbaf[c] * 255.0f);
        }
        width = image.width, height = image.height;
        return rgba;
    }
    // 8 bits a sample straight to RGBA (stb_image widens grey, grey + alpha and RGB as above): the output and the
    // decoder's inflated rows, never a float per sample (an 8192^2 texture took 1 GiB more through floats).
    requireDecodeBudget(path, header.width, header.height, 4, 2);
    int w = 0, h = 0, channels = 0;
    const auto* encoded = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int size = int(std::min<size_t>(bytes.size(), INT32_MAX));
    std::unique_ptr<stbi_uc, void (*)(void*)> data(stbi_load_from_memory(encoded, size, &w, &h, &channels, 4),
                                                   stbi_image_free);
    if (!data) throw Error(decodeFailure(path));
    rgba.assign(data.get(), data.get() + size_t(w) * h * 4);
    width = uint32_t(w), height = uint32_t(h);
    return rgba;
}

namespace {

ImageData loadPng(const std::string& path) {
    return decodePng(path, readImageFileBytes(path));
}

// Reads the data window into `samples` (interleaved float channels) a strip of rows at a time, growing the buffer
// only as rows arrive: a corrupt header can claim 32768x32768 pixels in a few hundred bytes, and OpenEXR throws
// at the first chunk the file lacks, so memory stays in proportion to the data the file really holds.
void readExrStrips(Imf::InputFile& file, const Imath::Box2i& window, const std::vector<std::string>& names,
                   std::vector<float>& samples) {
    const size_t width = size_t(int64_t(window.max.x) - window.min.x + 1);
    const size_t rowFloats = width * names.size();
    const int stripRows = int(std::max<size_t>(1, (size_t(1) << 18) / rowFloats)); // about 1 MiB a strip
    const size_t xStride = sizeof(float) * names.size(), yStride = xStride * width;
    for (int64_t y0 = window.min.y; y0 <= window.max.y; y0 += stripRows) {
        const int64_t y1 = std::min<int64_t>(window.max.y, y0 + stripRows - 1);
        samples.resize(size_t(y1 - window.min.y + 1) * rowFloats);
        // OpenEXR addresses the frame buffer with absolute data-window coordinates; Slice::Make shifts the base
        // by the window's origin itself (in integers: a pointer moved outside its buffer would be undefined).
        Imf::FrameBuffer frame;
        for (size_t c = 0; c < names.size(); ++c)
            frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, samples.data() + c, window.min, int64_t(width),
                                                    y1 - window.min.y + 1, xStride, yStride));
        file.setFrameBuffer(frame);
        file.readPixels(int(y0), int(y1));
    }
}

// An OpenEXR input stream over the file's bytes, read once: the header walk below and OpenEXR see the same data.
class MemoryIStream final : public Imf::IStream {
public:
    MemoryIStream(const std::string& name, std::vector<char> bytes)
        : Imf::IStream(name.c_str()), bytes_(std::move(bytes)) {}
    bool read(char c[], int n) override {
        if (n < 0 || size_t(n) > bytes_.size() - std::min(position_, bytes_.size()))
            throw std::runtime_error("unexpected end of file");
        std::memcpy(c, bytes_.data() + position_, size_t(n));
        position_ += size_t(n);
        return position_ < bytes_.size();
    }
    uint64_t tellg() override { return position_; }
    void seekg(uint64_t pos) override { position_ = size_t(std::min<uint64_t>(pos, bytes_.size())); }
    const std::vector<char>& bytes() const { return bytes_; }

private:
    std::vector<char> bytes_;
    size_t position_ = 0;
};

// The channels sward reads: R,G,B(,A), or the only channel, or Y of several.
std::vector<std::string> exrChannelsToRead(const std::string& path, const Imf::ChannelList& list) {
    if (list.findChannel("R") && list.findChannel("G") && list.findChannel("B")) {
        std::vector<std::string> names = {"R", "G", "B"};
        if (list.findChannel("A")) names.push_back("A");
        return names;
    }
    std::vector<std::string> all;
    for (auto it = list.begin(); it != list.end(); ++it) all.emplace_back(it.name());
    if (all.size() == 1) return all;
    require(list.findChannel("Y"), "image '" + path + "' has " + std::to_string(all.size()) +
                                       " EXR channels but neither R,G,B nor a single channel (or Y)");
    return {"Y"};
}


// `channel` empty: the channels exrChannelsToRead picks; else exactly that one.
ImageData loadExr(const std::string& path, const std::string& channel) {
    MemoryIStream stream(path, readImageFileBytes(path));
    requireSafeExrHeaders(path, stream.bytes());
    try {
        Imf::InputFile file(stream);
        const Imath::Box2i window = file.header().dataWindow();
        const int64_t width = int64_t(window.max.x) - window.min.x + 1;
        const int64_t height = int64_t(window.max.y) - window.min.y + 1;
        requireEdges(path, uint64_t(std::max<int64_t>(width, 0)), uint64_t(std::max<int64_t>(height, 0)));
        const Imf::ChannelList& list = file.header().channels();
        require(channel.empty() || list.findChannel(channel),
                "image '" + path + "' has no EXR channel '" + channel + "'");
        const std::vector<std::string> names = channel.empty() ? exrChannelsToRead(path, list)
                                                               : std::vector<std::string>{channel};
        requireDecodeBudget(path, uint64_t(width), uint64_t(height), names.size(), sizeof(float));
        ImageData image{.width = uint32_t(width),
                        .height = uint32_t(height),
                        .channels = uint32_t(names.size()),
                        .bitDepth = 32,
                        .source = path};
        readExrStrips(file, window, names, image.samples);
        return image;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error("cannot read OpenEXR image '" + path + "': " + e.what());
    }
}

} // namespace

std::string lowerExtension(const std::string& path) {
    size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || path.find_first_of("/\\", dot) != std::string::npos) return "";
    std::string ext = path.substr(dot + 1);
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

// Through the input door (common/input_file.h): a device (/dev/zero) or a pipe is refused without blocking.
std::vector<char> readImageFileBytes(const std::string& path) {
    const std::string bytes = readInputFile(path, "image", kMaxImageFileBytes);
    return std::vector<char>(bytes.begin(), bytes.end());
}

ImageData loadImage(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == "png") return loadPng(path);
    if (ext == "exr") return loadExr(path, {});
    throw Error("image '" + path + "' has unsupported format '." + ext + "' (use .png or .exr)");
}

ImageData loadExrChannel(const std::string& path, const std::string& channel) {
    require(lowerExtension(path) == "exr", "image '" + path + "' is not an OpenEXR file (channel '" + channel + "')");
    return loadExr(path, channel);
}

std::vector<std::string> exrChannelNames(const std::string& path) {
    require(lowerExtension(path) == "exr", "image '" + path + "' is not an OpenEXR file");
    MemoryIStream stream(path, readImageFileBytes(path));
    requireSafeExrHeaders(path, stream.bytes());
    try {
        Imf::InputFile file(stream);
        std::vector<std::string> names;
        for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it)
            names.emplace_back(it.name());
        return names;
    } catch (const std::exception& e) {
        throw Error("cannot read OpenEXR image '" + path + "': " + e.what());
    }
}

} // namespace sward

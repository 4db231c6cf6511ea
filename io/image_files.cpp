#include "io/image_files.h"

#include "common/error.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfOutputFile.h>

#include <png.h>
#include <zlib.h>

#include "common/atomic_file.h"
#include "common/half_float.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace sward {

namespace {

// One channel of an EXR file: pixel (x, y) of the channel is at base + x * xStride + y * width * xStride.
struct ExrChannel {
    const char* name;
    Imf::PixelType type;
    const void* base;
    size_t xStride; // bytes
};

// An OpenEXR output stream into memory: OutputFile writes the header, a placeholder line-offset table and the
// chunks, then seeks back to fill the table in, exactly as it does into a file, so the bytes are identical.
class MemoryOStream final : public Imf::OStream {
public:
    explicit MemoryOStream(const std::string& name) : Imf::OStream(name.c_str()) {}
    void write(const char c[], int n) override {
        if (position_ + size_t(n) > bytes_.size()) bytes_.resize(position_ + size_t(n));
        std::memcpy(bytes_.data() + position_, c, size_t(n));
        position_ += size_t(n);
    }
    uint64_t tellp() override { return position_; }
    void seekp(uint64_t pos) override { position_ = size_t(pos); }
    const std::vector<char>& bytes() const { return bytes_; }

private:
    std::vector<char> bytes_;
    size_t position_ = 0;
};

// The one place sward writes an OpenEXR file: single-part scanline, ZIP (lossless and deterministic, so identical
// pixels give identical files), one thread, encoded in memory and written atomically (common/atomic_file.h).
void writeExrChannels(const std::string& path, uint32_t width, uint32_t height, std::span<const ExrChannel> channels) {
    Imf::Header header{int(width), int(height)};
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer frame;
    for (const ExrChannel& c : channels) {
        header.channels().insert(c.name, Imf::Channel(c.type));
        // OpenEXR only reads the pixels when writing; its Slice takes a mutable pointer all the same.
        char* base = const_cast<char*>(static_cast<const char*>(c.base));
        frame.insert(c.name, Imf::Slice(c.type, base, c.xStride, c.xStride * width));
    }
    MemoryOStream stream(path);
    try {
        Imf::OutputFile file(stream, header, 1);
        file.setFrameBuffer(frame);
        file.writePixels(int(height));
    } catch (const std::exception&) { // OpenEXR's own text names internals, not the problem
        throw Error("cannot write '" + path + "': the OpenEXR encoder failed");
    }
    writeBytesAtomically(path, stream.bytes().data(), stream.bytes().size());
}

} // namespace

void writeExrRgbaHalf(const std::string& path, uint32_t width, uint32_t height, std::span<const uint16_t> rgbaHalf) {
    require(rgbaHalf.size() == size_t(width) * height * 4, "EXR colour buffer size does not match the image");
    const uint16_t* p = rgbaHalf.data();
    const ExrChannel channels[] = {
        {"R", Imf::HALF, p + 0, 8}, {"G", Imf::HALF, p + 1, 8}, {"B", Imf::HALF, p + 2, 8}, {"A", Imf::HALF, p + 3, 8}};
    writeExrChannels(path, width, height, channels);
}

void writeExrFloatChannels(const std::string& path, uint32_t width, uint32_t height,
                           const std::vector<std::string>& names, const std::vector<std::span<const float>>& planes) {
    require(names.size() == planes.size() && !names.empty(), "EXR channel names and planes do not match");
    for (auto& plane : planes)
        require(plane.size() == size_t(width) * height, "EXR plane size does not match the image");
    std::vector<ExrChannel> channels;
    for (size_t c = 0; c < names.size(); ++c)
        channels.push_back({names[c].c_str(), Imf::FLOAT, planes[c].data(), sizeof(float)});
    writeExrChannels(path, width, height, channels);
}

void writeExrDepth(const std::string& path, uint32_t width, uint32_t height, std::span<const float> depth,
                   bool withZCopy) {
    if (withZCopy)
        writeExrFloatChannels(path, width, height, {"Y", "Z"}, {depth, depth});
    else
        writeExrFloatChannels(path, width, height, {"Y"}, {depth});
}

void writeExr(const std::string& path, uint32_t width, uint32_t height, uint32_t channels,
              const std::vector<float>& samples) {
    require(channels == 1 || channels == 3 || channels == 4, "writeExr: channels must be 1, 3 or 4");
    require(samples.size() == size_t(width) * height * channels, "writeExr: sample count does not match the size");
    static const char* kRgba[] = {"R", "G", "B", "A"};
    std::vector<ExrChannel> list;
    for (uint32_t c = 0; c < channels; ++c)
        list.push_back({channels == 1 ? "Y" : kRgba[c], Imf::FLOAT, samples.data() + c, sizeof(float) * channels});
    writeExrChannels(path, width, height, list);
}

namespace {

// libpng's output into memory (png_set_write_fn).
void appendPngBytes(png_structp png, png_bytep data, size_t length) {
    auto* bytes = static_cast<std::vector<uint8_t>*>(png_get_io_ptr(png));
    bytes->insert(bytes->end(), data, data + length);
}
void flushPngBytes(png_structp) {}

// Encodes `rows` (height pointers to rows of width * channels samples of `bitDepth` bits, native byte order) into
// `bytes` with OpenCV 4's PNG encoder's settings and calls, so the files are those cv::imencode(".png") wrote before
// sward called libpng itself (test PngFiles.SameBytesAsOpenCvsEncoder): the sub filter, zlib's fastest level with
// its run-length strategy, 16-bit samples swapped to the file's big-endian order. False when libpng fails (it
// reports through longjmp, so no object with a destructor lives between setjmp and the calls).
bool encodePng(std::vector<uint8_t>& bytes, uint32_t width, uint32_t height, uint32_t channels, int bitDepth,
               png_bytepp rows) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    if (!png) return false;
    png_infop info = png_create_info_struct(png);
    bool encoded = false;
    if (info && setjmp(png_jmpbuf(png)) == 0) {
        png_set_write_fn(png, &bytes, appendPngBytes, flushPngBytes);
        png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
        png_set_compression_level(png, Z_BEST_SPEED);
        png_set_compression_strategy(png, Z_RLE);
        const int colour = channels == 1   ? PNG_COLOR_TYPE_GRAY
                           : channels == 3 ? PNG_COLOR_TYPE_RGB
                                           : PNG_COLOR_TYPE_RGBA;
        png_set_IHDR(png, info, width, height, bitDepth, colour, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                     PNG_FILTER_TYPE_DEFAULT);
        png_write_info(png, info);
        if (bitDepth == 16 && std::endian::native == std::endian::little) png_set_swap(png);
        png_write_image(png, rows);
        png_write_end(png, info);
        encoded = true;
    }
    png_destroy_write_struct(&png, &info);
    return encoded;
}

// writePng8 / writePng16. `Sample` is uint8_t or uint16_t.
template <typename Sample>
void writePngSamples(const std::string& path, uint32_t width, uint32_t height, uint32_t channels,
                     std::span<const Sample> samples) {
    require(channels == 1 || channels == 3 || channels == 4, "cannot write '" + path + "': a PNG of " +
                                                                 std::to_string(channels) +
                                                                 " channels (sward writes grey, RGB or RGBA)");
    require(samples.size() == size_t(width) * height * channels, "PNG buffer size does not match the image");
    require(width > 0 && height > 0 && width <= uint32_t(INT32_MAX) / channels && height <= uint32_t(INT32_MAX),
            "cannot write '" + path + "': the image is empty or too large for a PNG");
    // libpng copies each row before its transformations (the byte swap), so the samples are only read.
    std::vector<png_bytep> rows(height);
    for (uint32_t y = 0; y < height; ++y)
        rows[y] = reinterpret_cast<png_bytep>(const_cast<Sample*>(samples.data() + size_t(y) * width * channels));
    std::vector<uint8_t> bytes;
    require(encodePng(bytes, width, height, channels, int(sizeof(Sample) * 8), rows.data()),
            "cannot write '" + path + "': PNG encoding failed");
    writeBytesAtomically(path, bytes.data(), bytes.size());
}

} // namespace

void writePng8(const std::string& path, uint32_t width, uint32_t height, uint32_t channels,
               std::span<const uint8_t> pixels) {
    writePngSamples(path, width, height, channels, pixels);
}

void writePng16(const std::string& path, uint32_t width, uint32_t height, uint32_t channels,
                std::span<const uint16_t> samples) {
    writePngSamples(path, width, height, channels, samples);
}

namespace {

// Narkowicz's fit of the ACES filmic curve, on a luminance.
float filmicCurve(float x) {
    return std::clamp(x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}

} // namespace

std::array<float, 3> toneMap(std::array<float, 3> linear, float exposure) {
    std::array<float, 3> x;
    for (int c = 0; c < 3; ++c) x[c] = std::max(linear[c] * exposure, 0.0f);
    const float luminance = 0.2126f * x[0] + 0.7152f * x[1] + 0.0722f * x[2];
    if (!(luminance > 1e-8f)) return {0.0f, 0.0f, 0.0f};
    // The curve maps the luminance; the colour scales with it, so its hue and saturation are kept (the curve per
    // channel would steepen the ratios between channels in its toe: saturation 0.64 -> 0.83 on sward's meadow).
    const float mapped = filmicCurve(luminance);
    for (float& c : x) c *= mapped / luminance;
    // A channel that would clip pulls the colour towards grey at the same luminance until it fits: it fades to
    // white instead of shifting hue.
    const float peak = std::max({x[0], x[1], x[2]});
    if (peak > 1.0f)
        for (float& c : x) c = mapped + (c - mapped) * ((1.0f - mapped) / (peak - mapped));
    return x;
}

std::vector<uint8_t> tonemapPreview(std::span<const uint16_t> rgbaHalf, uint32_t width, uint32_t height,
                                    float exposure) {
    std::vector<uint8_t> rgb(size_t(width) * height * 3);
    for (size_t p = 0; p < size_t(width) * height; ++p) {
        const std::array<float, 3> mapped =
            toneMap({halfBitsToFloat(rgbaHalf[p * 4]), halfBitsToFloat(rgbaHalf[p * 4 + 1]),
                     halfBitsToFloat(rgbaHalf[p * 4 + 2])},
                    exposure);
        for (int c = 0; c < 3; ++c) {
            float x = std::clamp(mapped[c], 0.0f, 1.0f);
            x = x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f; // sRGB
            rgb[p * 3 + c] = uint8_t(std::clamp(x * 255.0f + 0.5f, 0.0f, 255.0f));
        }
    }
    return rgb;
}

void ensureWritableDirectory(const std::string& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir))
        throw Error("cannot create output folder '" + dir + "': " + (ec ? ec.message() : "not a directory"));
    std::string probe = dir + "/.sward-write-test";
    std::ofstream file(probe);
    bool ok = file.good() && (file << "ok").good();
    file.close();
    std::remove(probe.c_str());
    if (!ok) throw Error("cannot write to output folder '" + dir + "': permission denied or read-only");
}

} // namespace sward

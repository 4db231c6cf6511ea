#include "io/image_io.h"

#include "common/error.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <stb_image.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <memory>

namespace sward {

namespace {

std::string lowerExtension(const std::string& path) {
    size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || path.find_first_of("/\\", dot) != std::string::npos) return "";
    std::string ext = path.substr(dot + 1);
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

void requireEdges(const std::string& path, uint64_t width, uint64_t height) {
    require(width > 0 && height > 0 && width <= kMaxImageEdge && height <= kMaxImageEdge,
            "image '" + path + "' has size " + std::to_string(width) + "x" + std::to_string(height) +
                "; each edge must be 1.." + std::to_string(kMaxImageEdge) + " pixels");
}

// stb_image silently widens 1/2/4-bit grey images to 8 bits, so the true bit depth is read from the IHDR chunk,
// which the PNG specification requires to come first: 8-byte signature, length, "IHDR", width, height, depth, type.
struct PngHeader {
    uint32_t width, height, bitDepth, colorType;
};

PngHeader readPngHeader(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    require(file.good(), "cannot open image '" + path + "': file missing or unreadable");
    std::array<unsigned char, 26> b{};
    file.read(reinterpret_cast<char*>(b.data()), b.size());
    static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    require(file.gcount() == std::streamsize(b.size()) && std::equal(kSignature, kSignature + 8, b.begin()) &&
                std::equal(b.begin() + 12, b.begin() + 16, "IHDR"),
            "image '" + path + "' is not a valid PNG file (bad signature or header)");
    auto be32 = [&](size_t o) { return uint32_t(b[o]) << 24 | uint32_t(b[o + 1]) << 16 | b[o + 2] << 8 | b[o + 3]; };
    return {be32(16), be32(20), b[24], b[25]};
}

// Built only on failure: stbi_failure_reason() may be null, and require() evaluates its message eagerly.
std::string decodeFailure(const std::string& path) {
    const char* reason = stbi_failure_reason();
    return "cannot decode PNG '" + path + "': " + (reason ? reason : "corrupt or truncated data");
}

ImageData loadPng(const std::string& path) {
    PngHeader header = readPngHeader(path);
    requireEdges(path, header.width, header.height);
    const bool palette = header.colorType == 3;
    require(palette || header.bitDepth == 8 || header.bitDepth == 16,
            "image '" + path + "' has unsupported bit depth " + std::to_string(header.bitDepth) +
                " (PNG images must have 8 or 16 bits per sample)");
    const bool wide = !palette && header.bitDepth == 16;

    int width = 0, height = 0, channels = 0;
    ImageData image{.bitDepth = wide ? 16u : 8u, .source = path};
    if (wide) {
        std::unique_ptr<stbi_us, void (*)(void*)> data(stbi_load_16(path.c_str(), &width, &height, &channels, 0),
                                                       stbi_image_free);
        if (!data) throw Error(decodeFailure(path));
        image.samples.resize(size_t(width) * height * channels);
        for (size_t i = 0; i < image.samples.size(); ++i) image.samples[i] = float(data.get()[i]) / 65535.0f;
    } else {
        std::unique_ptr<stbi_uc, void (*)(void*)> data(stbi_load(path.c_str(), &width, &height, &channels, 0),
                                                       stbi_image_free);
        if (!data) throw Error(decodeFailure(path));
        image.samples.resize(size_t(width) * height * channels);
        for (size_t i = 0; i < image.samples.size(); ++i) image.samples[i] = float(data.get()[i]) / 255.0f;
    }
    image.width = uint32_t(width);
    image.height = uint32_t(height);
    image.channels = uint32_t(channels);
    return image;
}

ImageData loadExr(const std::string& path) {
    {
        std::ifstream probe(path, std::ios::binary);
        require(probe.good(), "cannot open image '" + path + "': file missing or unreadable");
    }
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i window = file.header().dataWindow();
        const int64_t width = int64_t(window.max.x) - window.min.x + 1;
        const int64_t height = int64_t(window.max.y) - window.min.y + 1;
        requireEdges(path, uint64_t(std::max<int64_t>(width, 0)), uint64_t(std::max<int64_t>(height, 0)));

        const Imf::ChannelList& list = file.header().channels();
        std::vector<std::string> names;
        if (list.findChannel("R") && list.findChannel("G") && list.findChannel("B")) {
            names = {"R", "G", "B"};
            if (list.findChannel("A")) names.push_back("A");
        } else {
            std::vector<std::string> all;
            for (auto it = list.begin(); it != list.end(); ++it) all.emplace_back(it.name());
            if (all.size() == 1)
                names = all;
            else if (list.findChannel("Y"))
                names = {"Y"};
            require(!names.empty(), "image '" + path + "' has " + std::to_string(all.size()) +
                                        " EXR channels but neither R,G,B nor a single channel (or Y)");
        }

        ImageData image{.width = uint32_t(width),
                    .height = uint32_t(height),
                    .channels = uint32_t(names.size()),
                    .bitDepth = 32,
                    .source = path};
        image.samples.resize(size_t(width) * height * names.size());
        const size_t xStride = sizeof(float) * names.size(), yStride = xStride * size_t(width);
        // OpenEXR addresses the frame buffer with absolute data-window coordinates, hence the shifted base.
        char* base = reinterpret_cast<char*>(image.samples.data()) - window.min.x * ptrdiff_t(xStride) -
                     window.min.y * ptrdiff_t(yStride);
        Imf::FrameBuffer frame;
        for (size_t c = 0; c < names.size(); ++c)
            frame.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xStride, yStride));
        file.setFrameBuffer(frame);
        file.readPixels(window.min.y, window.max.y);
        return image;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error("cannot read OpenEXR image '" + path + "': " + e.what());
    }
}

} // namespace

ImageData loadImage(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == "png") return loadPng(path);
    if (ext == "exr") return loadExr(path);
    throw Error("image '" + path + "' has unsupported format '." + ext + "' (use .png or .exr)");
}

} // namespace sward

#include "io/exr_header_check.h"

#include "common/error.h"
#include "io/image_io.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string_view>
#include <utility>

namespace sward {

namespace {

// OpenEXR reads these types by their layout, whatever size the file states.
constexpr std::pair<std::string_view, uint32_t> kFixedSizes[] = {
    {"box2i", 16},  {"box2f", 16}, {"chromaticities", 32}, {"compression", 1}, {"deepImageState", 1},
    {"double", 8},  {"envmap", 1}, {"float", 4},           {"int", 4},         {"keycode", 28},
    {"lineOrder", 1}, {"m33f", 36}, {"m33d", 72},          {"m44f", 64},       {"m44d", 128},
    {"rational", 8}, {"tiledesc", 9}, {"timecode", 8},     {"v2i", 8},         {"v2f", 8},
    {"v2d", 16},    {"v3i", 12},   {"v3f", 12},            {"v3d", 24}};

// Scan lines per chunk by compression (none, RLE, ZIPS, ZIP, PIZ, PXR24, B44, B44A, DWAA, DWAB).
constexpr uint32_t kLinesPerChunk[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};

struct Header {
    std::optional<std::array<int32_t, 4>> dataWindow; // min x, min y, max x, max y
    std::optional<std::array<uint32_t, 2>> tileSize;
    uint8_t compression = 0;
    uint32_t channels = 0;
    uint64_t bytesPerPixel = 0; // all channels, at full sampling
};

class HeaderWalk {
public:
    HeaderWalk(const std::string& path, std::span<const char> bytes)
        : b_(bytes), corrupt_("image '" + path + "' is not a valid OpenEXR file") {}

    // A NUL-terminated name; OpenEXR reads at most 256 bytes, so a longer one is refused rather than misread.
    std::string_view name() {
        const char* end = std::find(b_.data() + at_, b_.data() + std::min(b_.size(), at_ + 256), '\0');
        const size_t length = size_t(end - (b_.data() + at_));
        require(at_ + length < b_.size() && length < 256, corrupt_ + " (header cut short or a name over 255 bytes)");
        const std::string_view text(b_.data() + at_, length);
        at_ += length + 1;
        return text;
    }
    std::span<const char> take(uint64_t size, const char* what) {
        require(size <= b_.size() - at_, corrupt_ + " (" + what + " claims " + std::to_string(size) + " bytes; " +
                                             std::to_string(b_.size() - at_) + " follow)");
        const std::span<const char> value = b_.subspan(at_, size_t(size));
        at_ += size_t(size);
        return value;
    }
    uint32_t u32(const char* what) {
        uint32_t v = 0;
        std::memcpy(&v, take(4, what).data(), 4); // little-endian, as on every platform sward builds for
        return v;
    }
    const std::string& corrupt() const { return corrupt_; }

private:
    std::span<const char> b_;
    size_t at_ = 8;
    std::string corrupt_;
};

template <typename T> T readAt(std::span<const char> value, size_t offset) {
    T v;
    std::memcpy(&v, value.data() + offset, sizeof v);
    return v;
}

// chlist: per channel name, int32 pixel type, uint8 pLinear, 3 reserved, int32 x and y sampling; an empty name
// ends the list. Its length must be the stated size (OpenEXR reads it by layout).
void readChannels(HeaderWalk& walk, std::span<const char> value, Header& h) {
    size_t at = 0;
    while (true) {
        const char* end = std::find(value.data() + at, value.data() + value.size(), '\0');
        require(end != value.data() + value.size(), walk.corrupt() + " (channel list cut short)");
        const size_t length = size_t(end - (value.data() + at));
        at += length + 1;
        if (length == 0) break;
        require(value.size() - at >= 16, walk.corrupt() + " (channel list cut short)");
        const int32_t type = readAt<int32_t>(value, at);
        h.bytesPerPixel += type == 1 ? 2 : 4; // HALF 2, UINT and FLOAT 4
        ++h.channels;
        at += 16;
    }
    require(at == value.size(), walk.corrupt() + " (channel list of the wrong size)");
}

void readAttribute(HeaderWalk& walk, std::string_view name, std::string_view type, std::span<const char> value,
                   Header& h) {
    for (const auto& [fixedType, size] : kFixedSizes)
        if (type == fixedType)
            require(value.size() == size, walk.corrupt() + " (attribute '" + std::string(name) + "' of type " +
                                              std::string(type) + " has " + std::to_string(value.size()) +
                                              " bytes, not " + std::to_string(size) + ")");
    if (type == "chlist") readChannels(walk, value, h);
    if (type == "preview") {
        require(value.size() >= 8, walk.corrupt() + " (preview cut short)");
        const uint64_t pixels = uint64_t(readAt<uint32_t>(value, 0)) * readAt<uint32_t>(value, 4);
        require(value.size() == 8 + 4 * pixels, walk.corrupt() + " (preview of the wrong size)");
    }
    if (name == "dataWindow" && type == "box2i")
        h.dataWindow = {readAt<int32_t>(value, 0), readAt<int32_t>(value, 4), readAt<int32_t>(value, 8),
                        readAt<int32_t>(value, 12)};
    if (name == "tiles" && type == "tiledesc") h.tileSize = {readAt<uint32_t>(value, 0), readAt<uint32_t>(value, 4)};
    if (name == "compression" && type == "compression") h.compression = uint8_t(value[0]);
}

// What OpenEXR will allocate for this header, bounded before it does.
void requireBoundedAllocations(const std::string& path, const HeaderWalk& walk, const Header& h, size_t fileBytes) {
    require(h.dataWindow.has_value(), walk.corrupt() + " (no dataWindow)");
    const auto& w = *h.dataWindow;
    const int64_t width = int64_t(w[2]) - w[0] + 1, height = int64_t(w[3]) - w[1] + 1;
    require(width >= 1 && height >= 1 && width <= kMaxImageEdge && height <= kMaxImageEdge,
            "image '" + path + "' has size " + std::to_string(width) + "x" + std::to_string(height) +
                "; each edge must be 1.." + std::to_string(kMaxImageEdge) + " pixels");
    require(h.channels <= kMaxExrChannels, "image '" + path + "' has " + std::to_string(h.channels) +
                                               " channels, more than the " + std::to_string(kMaxExrChannels) +
                                               " sward reads");
    const uint32_t lines = h.compression < std::size(kLinesPerChunk) ? kLinesPerChunk[h.compression] : 1;
    const uint64_t chunkBytes = h.bytesPerPixel * uint64_t(width) * std::min<uint64_t>(lines, uint64_t(height));
    require(chunkBytes <= kMaxExrChunkBytes, "image '" + path + "' needs " + std::to_string(chunkBytes >> 20) +
                                                 " MiB per compressed chunk, over the limit of " +
                                                 std::to_string(kMaxExrChunkBytes >> 20) + " MiB");
    if (h.tileSize) {
        const uint64_t tx = (*h.tileSize)[0], ty = (*h.tileSize)[1];
        require(tx >= 1 && ty >= 1, walk.corrupt() + " (tile size 0)");
        const uint64_t tiles = ((uint64_t(width) + tx - 1) / tx) * ((uint64_t(height) + ty - 1) / ty);
        require(tiles * 8 <= fileBytes, walk.corrupt() + " (" + std::to_string(tiles) +
                                            " tiles, but their offset table cannot fit in the file)");
    }
}

} // namespace

void requireSafeExrHeaders(const std::string& path, std::span<const char> bytes) {
    HeaderWalk walk(path, bytes);
    require(bytes.size() >= 8 && std::memcmp(bytes.data(), "\x76\x2f\x31\x01", 4) == 0,
            walk.corrupt() + " (bad magic number)");
    const bool multiPart = (uint8_t(bytes[5]) & 0x10) != 0; // version field bit 12
    for (bool last = false; !last;) {
        Header h;
        bool empty = true;
        for (std::string_view name = walk.name(); !name.empty(); name = walk.name()) {
            empty = false;
            const std::string_view type = walk.name();
            const uint32_t size = walk.u32("an attribute size");
            readAttribute(walk, name, type, walk.take(size, "an attribute"), h);
        }
        if (!empty) requireBoundedAllocations(path, walk, h, bytes.size());
        last = !multiPart || empty;
    }
}

} // namespace sward

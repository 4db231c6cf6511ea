#include "interaction/state_file.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/input_file.h"
#include "vegetation/vegetation_params.h"

#include "shared/gpu_layout.h"

#include <bit>
#include <cassert>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iterator>

namespace sward {

namespace {

constexpr char kMagic[8] = {'S', 'W', 'A', 'R', 'D', 'S', 'T', '1'};
constexpr size_t kHeaderBytes = 8 + 4 + 4 + 8 + 8;
constexpr size_t kFieldBytes = 4 + 8;
constexpr size_t kChecksumBytes = 8;
constexpr size_t kTrackBlockBytes = 4 + 4 + sizeof(float) * gpu::kTrackBlockCells * gpu::kTrackBlockCells;
// The largest valid state: a tile of kMaxFieldsPerTileSide^2 fields, as many plants as there are plant ids and
// kMaxTrackBlocks blocks of ruts. A longer file is refused from its length, before it is read into memory.
constexpr uint64_t kMaxStateBytes = kHeaderBytes +
                                    uint64_t(kMaxFieldsPerTileSide) * kMaxFieldsPerTileSide * kFieldBytes +
                                    uint64_t(gpu::kMaxPlantInstances) * sizeof(gpu::PlantDynamic) + 4 +
                                    kMaxTrackBlocks * kTrackBlockBytes + kChecksumBytes;

// x86-64 and every target sward builds for are little-endian, so native byte copies are the file format.
static_assert(std::endian::native == std::endian::little);

template <class T> void put(std::vector<uint8_t>& out, T value) {
    const size_t at = out.size();
    out.resize(at + sizeof(T));
    std::memcpy(out.data() + at, &value, sizeof(T));
}

template <class T> T get(const std::vector<uint8_t>& in, size_t at) {
    T value;
    std::memcpy(&value, in.data() + at, sizeof(T));
    return value;
}

void putDynamics(std::vector<uint8_t>& out, std::span<const gpu::PlantDynamic> dynamics) {
    const size_t at = out.size();
    out.resize(at + dynamics.size_bytes());
    if (!dynamics.empty()) std::memcpy(out.data() + at, dynamics.data(), dynamics.size_bytes());
}

void putTracks(std::vector<uint8_t>& out, const TrackBlocks& tracks) {
    require(tracks.size() <= kMaxTrackBlocks, "the ground tracks have more than " + std::to_string(kMaxTrackBlocks) +
                                                  " blocks: too many for a state file");
    put(out, uint32_t(tracks.size()));
    for (const auto& [key, block] : tracks) {
        put(out, key.x);
        put(out, key.y);
        const size_t at = out.size();
        out.resize(at + block.size() * sizeof(float));
        std::memcpy(out.data() + at, block.data(), block.size() * sizeof(float));
    }
}

// The track section at `at` (its size checked): a block count, then the blocks ascending (y, x), depths >= 0.
TrackBlocks readTracks(const std::vector<uint8_t>& bytes, size_t at, const std::string& what) {
    const uint32_t count = get<uint32_t>(bytes, at); // loadInteractionState checked the size
    at += 4;
    TrackBlocks tracks;
    for (uint32_t k = 0; k < count; ++k, at += kTrackBlockBytes) {
        const TrackBlockKey key{get<int32_t>(bytes, at), get<int32_t>(bytes, at + 4)};
        require(tracks.empty() || tracks.rbegin()->first < key,
                what + "track block " + std::to_string(k) + " is out of order (blocks ascend by y, then x)");
        TrackBlock block(gpu::kTrackBlockCells * gpu::kTrackBlockCells);
        std::memcpy(block.data(), bytes.data() + at + 8, block.size() * sizeof(float));
        for (float d : block)
            require(std::isfinite(d) && d >= 0.0f, what + "track block " + std::to_string(k) + " has a rut depth " +
                                                       std::to_string(d) + " (must be finite and >= 0)");
        tracks.emplace_hint(tracks.end(), key, std::move(block));
    }
    return tracks;
}

// The whole file, refused from its length when longer than `maxBytes` (before it is read into memory).
std::vector<uint8_t> readStateBytes(const std::string& path, uint64_t maxBytes, const std::string& noun) {
    // The input door: a FIFO or a device is refused without blocking.
    const uint64_t size = openInputFile(path, noun).size();
    require(size <= maxBytes, path + ": not a valid " + noun + ": " + std::to_string(size) +
                                  " bytes, more than the largest valid state (" + std::to_string(maxBytes) + " bytes)");
    return readInputBytes(path, noun, maxBytes);
}

// Magic, a header and checksum's length, and the version (the uint32 after the magic) of a state file.
void requireHeader(const std::vector<uint8_t>& bytes, const char (&magic)[8], size_t headerBytes, uint32_t version,
                   const std::string& what) {
    require(bytes.size() >= 8 && std::memcmp(bytes.data(), magic, 8) == 0,
            what + "wrong magic (expected " + std::string(magic, 8) + ")");
    require(bytes.size() >= headerBytes + kChecksumBytes,
            what + "truncated (" + std::to_string(bytes.size()) + " bytes)");
    const uint32_t stored = get<uint32_t>(bytes, 8);
    require(stored == version, what + "unsupported version " + std::to_string(stored) + " (expected " +
                                   std::to_string(version) + ")");
}

// The last 8 bytes are the FNV-1a 64 of all before them. Requires bytes.size() >= kChecksumBytes.
void requireChecksum(const std::vector<uint8_t>& bytes, const std::string& what) {
    const uint64_t stored = get<uint64_t>(bytes, bytes.size() - kChecksumBytes);
    require(stored == fnv1a64(std::span(bytes.data(), bytes.size() - kChecksumBytes)),
            what + "checksum mismatch (the file is corrupt)");
}

} // namespace

uint64_t fnv1a64(std::span<const uint8_t> bytes) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (uint8_t b : bytes) h = (h ^ b) * 0x100000001b3ull;
    return h;
}

void saveInteractionState(const std::string& path, const InteractionState& state) {
    assert(state.fieldActive.size() == state.lastContactTick.size());
    std::vector<uint8_t> bytes;
    bytes.reserve(kHeaderBytes + state.fieldActive.size() * kFieldBytes +
                  state.dynamics.size() * sizeof(gpu::PlantDynamic) + kChecksumBytes);
    bytes.insert(bytes.end(), std::begin(kMagic), std::end(kMagic));
    put(bytes, kStateFileVersion);
    put(bytes, uint32_t(state.fieldActive.size()));
    put(bytes, state.tick);
    put(bytes, uint64_t(state.dynamics.size()));
    for (size_t f = 0; f < state.fieldActive.size(); ++f) {
        put(bytes, uint32_t(state.fieldActive[f] ? 1u : 0u));
        put(bytes, state.lastContactTick[f]);
    }
    putDynamics(bytes, state.dynamics);
    putTracks(bytes, state.tracks);
    put(bytes, fnv1a64(bytes));

    writeBytesAtomically(path, bytes.data(), bytes.size());
}

InteractionState loadInteractionState(const std::string& path) {
    const std::vector<uint8_t> bytes = readStateBytes(path, kMaxStateBytes, "interaction state file");
    const std::string what = path + ": not a valid interaction state file: ";
    requireHeader(bytes, kMagic, kHeaderBytes, kStateFileVersion, what);
    const uint32_t fields = get<uint32_t>(bytes, 12);
    const uint64_t tick = get<uint64_t>(bytes, 16);
    const uint64_t plants = get<uint64_t>(bytes, 24);
    // Sizes are checked against the file length before anything is allocated, so a corrupt count cannot ask for
    // terabytes.
    const uint64_t available = bytes.size() - kHeaderBytes - kChecksumBytes;
    const bool fits = uint64_t(fields) * kFieldBytes <= available &&
                      plants <= (available - uint64_t(fields) * kFieldBytes) / sizeof(gpu::PlantDynamic);
    const uint64_t tracksAt = kHeaderBytes + uint64_t(fields) * kFieldBytes + plants * sizeof(gpu::PlantDynamic);
    require(fits && tracksAt + 4 <= bytes.size() - kChecksumBytes,
            what + "truncated (" + std::to_string(bytes.size()) + " bytes for " + std::to_string(fields) +
                " fields and " + std::to_string(plants) + " plants)");
    const uint64_t blocks = get<uint32_t>(bytes, size_t(tracksAt));
    const uint64_t expected = tracksAt + 4 + blocks * kTrackBlockBytes + kChecksumBytes;
    require(expected == bytes.size(), what + "size " + std::to_string(bytes.size()) + " bytes, expected " +
                                          std::to_string(expected) + " for " + std::to_string(fields) + " fields, " +
                                          std::to_string(plants) + " plants and " + std::to_string(blocks) +
                                          " track blocks");
    requireChecksum(bytes, what);

    InteractionState state;
    state.tick = tick;
    state.fieldActive.resize(fields);
    state.lastContactTick.resize(fields);
    size_t at = kHeaderBytes;
    for (uint32_t f = 0; f < fields; ++f, at += kFieldBytes) {
        const uint32_t active = get<uint32_t>(bytes, at);
        require(active <= 1, what + "field " + std::to_string(f) + " has active flag " + std::to_string(active));
        state.fieldActive[f] = uint8_t(active);
        state.lastContactTick[f] = get<uint64_t>(bytes, at + 4);
    }
    state.dynamics.resize(plants);
    if (plants > 0) std::memcpy(state.dynamics.data(), bytes.data() + at, plants * sizeof(gpu::PlantDynamic));
    state.tracks = readTracks(bytes, at + plants * sizeof(gpu::PlantDynamic), what);
    return state;
}

namespace {

constexpr char kWorldMagic[8] = {'S', 'W', 'A', 'R', 'D', 'W', 'S', '1'};
constexpr size_t kWorldHeaderBytes = 8 + 4 + 4 + 8 + 4 + 4 + 8;
constexpr size_t kWorldTileBytes = 4 + 4 + 4;
constexpr size_t kWorldFieldBytes = 4 + 4 + 8 + 4;
// Far beyond any touched world a machine can hold; a longer file is refused from its length alone.
constexpr uint64_t kMaxWorldStateBytes = uint64_t(1) << 36;

// Reads the world state's body in order; every count is checked against the bytes left before it is used.
class WorldStateReader {
public:
    WorldStateReader(const std::vector<uint8_t>& bytes, std::string what)
        : bytes_(bytes), end_(bytes.size() - kChecksumBytes), what_(std::move(what)) {}
    template <class T> T take() {
        need(sizeof(T), "");
        const T value = get<T>(bytes_, at_);
        at_ += sizeof(T);
        return value;
    }
    void need(uint64_t n, const std::string& what) const {
        require(n <= end_ - at_, what_ + "truncated (" + std::to_string(bytes_.size()) + " bytes" + what + ")");
    }
    void skip(size_t n) { at_ += n; }
    const uint8_t* data() const { return bytes_.data() + at_; }
    bool done() const { return at_ == end_; }
    const std::string& what() const { return what_; }

private:
    const std::vector<uint8_t>& bytes_;
    size_t at_ = kWorldHeaderBytes, end_;
    std::string what_;
};

TouchedField readTouchedField(WorldStateReader& r, const std::string& where) {
    TouchedField f;
    f.field = r.take<uint32_t>();
    const uint32_t active = r.take<uint32_t>();
    require(active <= 1, r.what() + where + " field " + std::to_string(f.field) + " has active flag " +
                             std::to_string(active));
    f.active = active != 0;
    f.lastContactTick = r.take<uint64_t>();
    const uint32_t plants = r.take<uint32_t>();
    r.need(uint64_t(plants) * sizeof(gpu::PlantDynamic), " for " + std::to_string(plants) + " plants");
    f.dynamics.resize(plants);
    if (plants > 0) std::memcpy(f.dynamics.data(), r.data(), plants * sizeof(gpu::PlantDynamic));
    r.skip(plants * sizeof(gpu::PlantDynamic));
    return f;
}

TileInteractionState readTileState(WorldStateReader& r, const WorldInteractionState& world,
                                   const TileInteractionState* previous) {
    TileInteractionState tile;
    tile.coord = {r.take<int32_t>(), r.take<int32_t>()};
    const std::string where = "tile (" + std::to_string(tile.coord.x) + ", " + std::to_string(tile.coord.y) + ")";
    require(tile.coord.x >= 0 && tile.coord.y >= 0 && uint32_t(tile.coord.x) < world.tilesX &&
                uint32_t(tile.coord.y) < world.tilesY,
            r.what() + where + " is outside the world of " + std::to_string(world.tilesX) + " x " +
                std::to_string(world.tilesY) + " tiles");
    require(!previous || std::pair(previous->coord.y, previous->coord.x) < std::pair(tile.coord.y, tile.coord.x),
            r.what() + where + " is out of order (tiles ascend by y, then x)");
    const uint32_t fields = r.take<uint32_t>();
    r.need(uint64_t(fields) * kWorldFieldBytes, " for " + std::to_string(fields) + " fields");
    tile.fields.reserve(fields);
    for (uint32_t k = 0; k < fields; ++k) {
        tile.fields.push_back(readTouchedField(r, where));
        require(k == 0 || tile.fields[k - 1].field < tile.fields[k].field,
                r.what() + where + " has its fields out of order");
    }
    return tile;
}

} // namespace

void saveWorldState(const std::string& path, const WorldInteractionState& state) {
    std::vector<uint8_t> bytes(std::begin(kWorldMagic), std::end(kWorldMagic));
    put(bytes, state.tracks.empty() ? kWorldStateFileVersion : kWorldStateTracksVersion);
    put(bytes, uint32_t(state.tiles.size()));
    put(bytes, state.tick);
    put(bytes, state.tilesX);
    put(bytes, state.tilesY);
    put(bytes, state.seed);
    for (const TileInteractionState& tile : state.tiles) {
        assert(uint32_t(tile.coord.x) < state.tilesX && uint32_t(tile.coord.y) < state.tilesY);
        put(bytes, tile.coord.x);
        put(bytes, tile.coord.y);
        put(bytes, uint32_t(tile.fields.size()));
        for (const TouchedField& f : tile.fields) {
            put(bytes, f.field);
            put(bytes, uint32_t(f.active ? 1u : 0u));
            put(bytes, f.lastContactTick);
            put(bytes, uint32_t(f.dynamics.size()));
            putDynamics(bytes, f.dynamics);
        }
    }
    if (!state.tracks.empty()) putTracks(bytes, state.tracks);
    put(bytes, fnv1a64(bytes));
    writeBytesAtomically(path, bytes.data(), bytes.size());
}

WorldInteractionState loadWorldState(const std::string& path, uint64_t seed) {
    const std::vector<uint8_t> bytes = readStateBytes(path, kMaxWorldStateBytes, "world state file");
    const std::string what = path + ": not a valid world state file: ";
    const bool tracks = bytes.size() >= 12 && get<uint32_t>(bytes, 8) == kWorldStateTracksVersion;
    requireHeader(bytes, kWorldMagic, kWorldHeaderBytes, tracks ? kWorldStateTracksVersion : kWorldStateFileVersion,
                  what);
    // The checksum first: a corrupt count is then reported as corruption, not as a truncated file.
    requireChecksum(bytes, what);
    WorldInteractionState state;
    const uint32_t tiles = get<uint32_t>(bytes, 12);
    state.tick = get<uint64_t>(bytes, 16);
    state.tilesX = get<uint32_t>(bytes, 24);
    state.tilesY = get<uint32_t>(bytes, 28);
    state.seed = get<uint64_t>(bytes, 32);
    // Refused at load: restoring compares the plants of resident tiles only, so a state of another seed would
    // otherwise pass and fail at a later render, when one of its tiles first becomes resident.
    require(state.seed == seed, path + ": the world state was saved from a world of seed " +
                                    std::to_string(state.seed) + "; this scene's seed is " + std::to_string(seed));
    WorldStateReader r(bytes, what);
    r.need(uint64_t(tiles) * kWorldTileBytes, " for " + std::to_string(tiles) + " tiles");
    state.tiles.reserve(tiles);
    for (uint32_t t = 0; t < tiles; ++t)
        state.tiles.push_back(readTileState(r, state, t == 0 ? nullptr : &state.tiles.back()));
    if (tracks) {
        const uint32_t blocks = r.take<uint32_t>();
        r.need(uint64_t(blocks) * kTrackBlockBytes, " for " + std::to_string(blocks) + " track blocks");
        state.tracks = readTracks(bytes, size_t(r.data() - bytes.data()) - 4, what);
        r.skip(blocks * kTrackBlockBytes);
    }
    require(r.done(), what + "bytes left after the last tile");
    return state;
}

} // namespace sward

#include "interaction/state_file.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "vegetation/vegetation_params.h"

#include "shared/gpu_layout.h"

#include <bit>
#include <cassert>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace sward {

namespace {

constexpr char kMagic[8] = {'S', 'W', 'A', 'R', 'D', 'S', 'T', '1'};
constexpr size_t kHeaderBytes = 8 + 4 + 4 + 8 + 8;
constexpr size_t kFieldBytes = 4 + 8;
constexpr size_t kChecksumBytes = 8;
// The largest valid state: a tile of kMaxFieldsPerTileSide^2 fields and as many plants as there are plant ids. A
// longer file is refused from its length, before it is read into memory.
constexpr uint64_t kMaxStateBytes = kHeaderBytes +
                                    uint64_t(kMaxFieldsPerTileSide) * kMaxFieldsPerTileSide * kFieldBytes +
                                    uint64_t(gpu::kMaxPlantInstances) * sizeof(gpu::PlantDynamic) + kChecksumBytes;

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
    const size_t at = bytes.size();
    bytes.resize(at + state.dynamics.size() * sizeof(gpu::PlantDynamic));
    if (!state.dynamics.empty())
        std::memcpy(bytes.data() + at, state.dynamics.data(), state.dynamics.size() * sizeof(gpu::PlantDynamic));
    put(bytes, fnv1a64(bytes));

    writeBytesAtomically(path, bytes.data(), bytes.size());
}

InteractionState loadInteractionState(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    require(bool(in), path + ": cannot open the interaction state file");
    std::error_code ec;
    const uint64_t size = std::filesystem::file_size(path, ec);
    require(!ec, path + ": cannot read the interaction state file");
    require(size <= kMaxStateBytes, path + ": not a valid interaction state file: " + std::to_string(size) +
                                               " bytes, more than the largest valid state (" +
                                               std::to_string(kMaxStateBytes) + " bytes)");
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string what = path + ": not a valid interaction state file: ";
    require(bytes.size() >= 8 && std::memcmp(bytes.data(), kMagic, 8) == 0, what + "wrong magic (expected SWARDST1)");
    require(bytes.size() >= kHeaderBytes + kChecksumBytes,
            what + "truncated (" + std::to_string(bytes.size()) + " bytes)");
    const uint32_t version = get<uint32_t>(bytes, 8);
    require(version == kStateFileVersion, what + "unsupported version " + std::to_string(version) + " (expected " +
                                              std::to_string(kStateFileVersion) + ")");
    const uint32_t fields = get<uint32_t>(bytes, 12);
    const uint64_t tick = get<uint64_t>(bytes, 16);
    const uint64_t plants = get<uint64_t>(bytes, 24);
    // Sizes are checked against the file length before anything is allocated, so a corrupt count cannot ask for
    // terabytes.
    const uint64_t available = bytes.size() - kHeaderBytes - kChecksumBytes;
    const bool fits = uint64_t(fields) * kFieldBytes <= available &&
                      plants <= (available - uint64_t(fields) * kFieldBytes) / sizeof(gpu::PlantDynamic);
    const uint64_t expected =
        fits ? kHeaderBytes + uint64_t(fields) * kFieldBytes + plants * sizeof(gpu::PlantDynamic) + kChecksumBytes : 0;
    require(fits, what + "truncated (" + std::to_string(bytes.size()) + " bytes for " + std::to_string(fields) +
                      " fields and " + std::to_string(plants) + " plants)");
    require(expected == bytes.size(), what + "size " + std::to_string(bytes.size()) + " bytes, expected " +
                                          std::to_string(expected) + " for " + std::to_string(fields) + " fields and " +
                                          std::to_string(plants) + " plants");
    const uint64_t stored = get<uint64_t>(bytes, bytes.size() - kChecksumBytes);
    require(stored == fnv1a64(std::span(bytes.data(), bytes.size() - kChecksumBytes)),
            what + "checksum mismatch (the file is corrupt)");

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
    return state;
}

} // namespace sward

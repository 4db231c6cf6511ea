// Save / restore of the interaction state (issue 6): the simulation tick, every field's activity bookkeeping and
// every plant's dynamic record, so a scenario resumes bitwise exactly where it stopped.
//
// File layout (little-endian, packed, no padding):
//   "SWARDST1"                      8-byte magic
//   uint32 version (kStateFileVersion), uint32 field count, uint64 tick, uint64 plant count
//   per field: uint32 active (0 or 1), uint64 last contact tick
//   per plant: gpu::PlantDynamic (uint32 bend, uint32 state), in the tile's record-buffer order
//   uint64 FNV-1a 64 of every byte before it
// Written to "<path>.tmp" and renamed over path, so a crash never leaves a half-written state behind.
#pragma once

#include "shared/plant_layout.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sward {

inline constexpr uint32_t kStateFileVersion = 1;

struct InteractionState {
    uint64_t tick = 0;                       // the next tick to simulate
    std::vector<uint8_t> fieldActive;        // per field, 0 or 1
    std::vector<uint64_t> lastContactTick;   // per field, parallel to fieldActive
    std::vector<gpu::PlantDynamic> dynamics; // every plant of the tile
};

// FNV-1a 64 of a byte range.
uint64_t fnv1a64(std::span<const uint8_t> bytes);

// Writes state atomically (tmp + rename). Requires fieldActive and lastContactTick of equal size. Throws
// sward::Error naming the file when it cannot be written.
void saveInteractionState(const std::string& path, const InteractionState& state);

// Reads a state file; throws sward::Error naming the file and the problem (missing, wrong magic, unsupported
// version, truncated or oversized, bad active flag, checksum mismatch).
InteractionState loadInteractionState(const std::string& path);

} // namespace sward

// Save / restore of the interaction state (issue 6): the simulation tick, every field's activity bookkeeping and
// every plant's dynamic record, so a scenario resumes bitwise exactly where it stopped.
//
// File layout (little-endian, packed, no padding):
//   "SWARDST1"                      8-byte magic
//   uint32 version (kStateFileVersion), uint32 field count, uint64 tick, uint64 plant count
//   per field: uint32 active (0 or 1), uint64 last contact tick
//   per plant: gpu::PlantDynamic (uint32 bend, uint32 state), in the tile's record-buffer order
//   uint32 track block count (interaction/ground_tracks.h), per block ascending (y, x):
//     int32 x, int32 y, float rut depth of its kTrackBlockCells^2 own lattice vertices, row after row
//   uint64 FNV-1a 64 of every byte before it
// Written to "<path>.tmp" and renamed over path, so a crash never leaves a half-written state behind.
//
// The world state (a world of many tiles, scene/world_tiles.h) keeps only the touched fields of each tile
// (interaction/tile_state.h), resident or evicted:
//   "SWARDWS1"                      8-byte magic
//   uint32 version (kWorldStateFileVersion), uint32 tile count, uint64 tick, uint32 tiles x, uint32 tiles y,
//   uint64 seed (the scene's: every tile's plants grow from it)
//   per tile, ascending (y, x): int32 x, int32 y, uint32 field count
//     per field, ascending index: uint32 field, uint32 active (0 or 1), uint64 last contact tick,
//                                 uint32 plant count, that many gpu::PlantDynamic
//   version 3 only (a world with ruts): the track section, as the tile state's
//   uint64 FNV-1a 64 of every byte before it
// written and checked like the tile state file.
#pragma once

#include "interaction/ground_tracks.h"
#include "interaction/tile_state.h"

#include "shared/plant_layout.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sward {

inline constexpr uint32_t kStateFileVersion = 2; // 2: ground tracks
// Most rut blocks a state file holds (269 MB of them, 42,000 m^2 of ruts).
inline constexpr uint64_t kMaxTrackBlocks = uint64_t(1) << 16;

struct InteractionState {
    uint64_t tick = 0;                       // the next tick to simulate
    std::vector<uint8_t> fieldActive;        // per field, 0 or 1
    std::vector<uint64_t> lastContactTick;   // per field, parallel to fieldActive
    std::vector<gpu::PlantDynamic> dynamics; // every plant of the tile
    TrackBlocks tracks;                      // the ruts pressed into the ground (GroundTracks::blocks)
};

// FNV-1a 64 of a byte range.
uint64_t fnv1a64(std::span<const uint8_t> bytes);

// Writes state atomically (tmp + rename). Requires fieldActive and lastContactTick of equal size. Throws
// sward::Error naming the file when it cannot be written.
void saveInteractionState(const std::string& path, const InteractionState& state);

// Reads a state file; throws sward::Error naming the file and the problem (missing, wrong magic, unsupported
// version, truncated or oversized, bad active flag, checksum mismatch).
InteractionState loadInteractionState(const std::string& path);

inline constexpr uint32_t kWorldStateFileVersion = 2; // 2: the seed
// A world state holding ruts: version 2 and the track section. A world without ruts still writes version 2, so its
// files stay the bytes they were; both versions are read.
inline constexpr uint32_t kWorldStateTracksVersion = 3;

struct WorldInteractionState {
    uint64_t tick = 0;                       // the next tick to simulate
    uint32_t tilesX = 0, tilesY = 0;         // the world's size in tiles
    uint64_t seed = 0;                       // the scene's seed: a state of another seed fits no tile's plants
    std::vector<TileInteractionState> tiles; // tiles with touched fields, ascending (y, x)
    TrackBlocks tracks;                      // the world's ruts (GroundTracks::blocks), world-wide
};

// Writes a world state atomically. Requires tiles inside the world, ascending (y, x), each field list ascending.
// Throws sward::Error naming the file when it cannot be written.
void saveWorldState(const std::string& path, const WorldInteractionState& state);

// Reads the world state file of a scene of `seed`; throws sward::Error naming the file and the problem (missing,
// wrong magic, version, truncated or oversized, another seed (naming both), a tile outside the world or out of
// order, a bad active flag, checksum mismatch). Sizes are checked against the file's length before anything is
// allocated.
WorldInteractionState loadWorldState(const std::string& path, uint64_t seed);

} // namespace sward

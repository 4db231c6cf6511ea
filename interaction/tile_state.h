// The interaction state of one tile, kept compactly: only the fields a collider has touched (their dynamic records
// and activity). Every other field of a freshly generated tile is at rest, so a world tile that was evicted and is
// generated again is restored bitwise by writing these fields back (scene/world_tiles.h).
#pragma once

#include "vegetation/vegetation_tile.h"

#include "shared/plant_layout.h"

#include <cstdint>
#include <string>
#include <vector>

namespace sward {

struct TouchedField {
    uint32_t field = 0;                      // index in the tile (row-major, x fastest)
    bool active = false;                     // FieldVegetation::active
    uint64_t lastContactTick = 0;            // FieldVegetation::timeStamp
    std::vector<gpu::PlantDynamic> dynamics; // the field's dynamic records, in record order
};

struct TileInteractionState {
    TileCoord coord;
    std::vector<TouchedField> fields; // ascending field index; empty: the tile is as generated
    uint64_t bytes() const;           // memory held by the records and the field headers
};

// A field differs from a freshly generated one: active, a last contact tick or a dynamic record not at rest.
bool fieldTouched(const FieldVegetation& field);

// The touched fields of `tile`.
TileInteractionState captureTouchedFields(const VegetationTile& tile);

// Throws sward::Error starting with `what` unless `state` fits `tile`: field indices ascending and inside the tile, each
// field's plant count the tile's (else the state belongs to another world, seed or density).
void checkTouchedFields(const VegetationTile& tile, const TileInteractionState& state, const std::string& what);

// Makes `tile` hold exactly `state`: its fields written back, every other touched field reset to rest. Checks
// first (checkTouchedFields): on an error the tile is unchanged.
void restoreTouchedFields(VegetationTile& tile, const TileInteractionState& state, const std::string& what);

} // namespace sward

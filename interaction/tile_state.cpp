#include "interaction/tile_state.h"

#include "common/error.h"
#include "vegetation/records.h"

#include <algorithm>
#include <cstring>

namespace sward {

namespace {

bool atRest(const gpu::PlantDynamic& d, const gpu::PlantDynamic& rest) {
    return std::memcmp(&d, &rest, sizeof d) == 0;
}

void resetField(FieldVegetation& field) {
    field.active = false;
    field.timeStamp = 0;
    std::fill(field.dynamicRecords.begin(), field.dynamicRecords.end(), restingPlantDynamic());
}

} // namespace

uint64_t TileInteractionState::bytes() const {
    uint64_t total = sizeof(*this);
    for (const TouchedField& f : fields) total += sizeof(f) + f.dynamics.size() * sizeof(gpu::PlantDynamic);
    return total;
}

bool fieldTouched(const FieldVegetation& field) {
    if (field.active || field.timeStamp != 0) return true;
    const gpu::PlantDynamic rest = restingPlantDynamic();
    return !std::all_of(field.dynamicRecords.begin(), field.dynamicRecords.end(),
                        [&](const gpu::PlantDynamic& d) { return atRest(d, rest); });
}

TileInteractionState captureTouchedFields(const VegetationTile& tile) {
    TileInteractionState state{.coord = tile.coord};
    for (uint32_t f = 0; f < tile.fields.size(); ++f) {
        const FieldVegetation& field = tile.fields[f];
        if (fieldTouched(field))
            state.fields.push_back({.field = f,
                                    .active = field.active,
                                    .lastContactTick = field.timeStamp,
                                    .dynamics = field.dynamicRecords});
    }
    return state;
}

void checkTouchedFields(const VegetationTile& tile, const TileInteractionState& state, const std::string& what) {
    for (size_t k = 0; k < state.fields.size(); ++k) {
        const TouchedField& f = state.fields[k];
        require(k == 0 || state.fields[k - 1].field < f.field, what + ": its fields are not in ascending order");
        require(f.field < tile.fields.size(), what + ": field " + std::to_string(f.field) + " is outside the tile (" +
                                                  std::to_string(tile.fields.size()) + " fields)");
        const uint32_t plants = tile.fields[f.field].plantCount();
        require(f.dynamics.size() == plants, what + ": field " + std::to_string(f.field) + " holds " +
                                                 std::to_string(f.dynamics.size()) + " plants in the state but " +
                                                 std::to_string(plants) +
                                                 " in the tile (another seed, density or world)");
    }
}

void restoreTouchedFields(VegetationTile& tile, const TileInteractionState& state, const std::string& what) {
    // Check everything first, so a state of another world leaves the tile as it was.
    checkTouchedFields(tile, state, what);
    size_t next = 0;
    for (uint32_t i = 0; i < tile.fields.size(); ++i) {
        FieldVegetation& field = tile.fields[i];
        if (next < state.fields.size() && state.fields[next].field == i) {
            const TouchedField& f = state.fields[next++];
            field.active = f.active;
            field.timeStamp = f.lastContactTick;
            field.dynamicRecords = f.dynamics;
        } else if (fieldTouched(field)) {
            resetField(field);
        }
    }
}

} // namespace sward

#include "interaction/interaction.h"

#include "common/error.h"

#include <cassert>

namespace sward {

InteractionWorld::InteractionWorld(const VegetationTile& tile, const VegetationParams& vegetation,
                                   const InteractionParams& params, uint32_t threads)
    : tile_(&tile), params_(params), pass_(tile, vegetation, params), threads_(threads), active_(tile.fields.size(), 0),
      lastContact_(tile.fields.size(), 0) {
    assert(threads >= 1);
    for (const FieldVegetation& field : tile.fields) {
        // Contacts and simulateOnCpu index the tile's record buffers: fields must be packed in field order.
        assert(field.firstPlant == plantCount_);
        plantCount_ += field.plantCount();
    }
}

void InteractionWorld::setThreads(uint32_t threads) {
    assert(threads >= 1);
    threads_ = threads;
}

void InteractionWorld::resumeAt(uint64_t tick) {
    tick_ = tick;
    for (size_t f = 0; f < tile_->fields.size(); ++f) {
        active_[f] = tile_->fields[f].active ? 1 : 0;
        lastContact_[f] = tile_->fields[f].timeStamp;
    }
}

void InteractionWorld::writeActivity(VegetationTile& tile) const {
    assert(&tile == tile_);
    for (size_t f = 0; f < tile.fields.size(); ++f) {
        tile.fields[f].active = active_[f] != 0;
        tile.fields[f].timeStamp = lastContact_[f];
    }
}

TickResult InteractionWorld::step(std::span<const Collider> colliders) {
    TickResult result;
    static_cast<CollisionResult&>(result) = pass_.run(colliders, threads_);
    result.tick = tick_;
    for (uint32_t f : result.touchedFields) {
        active_[f] = 1;
        lastContact_[f] = tick_;
    }
    for (size_t f = 0; f < active_.size(); ++f)
        if (active_[f] && tick_ - lastContact_[f] >= params_.recovery.restTicks) active_[f] = 0;
    result.activeFields = activeFields();
    ++tick_;
    return result;
}

std::vector<uint32_t> InteractionWorld::activeFields() const {
    std::vector<uint32_t> fields;
    for (size_t f = 0; f < active_.size(); ++f)
        if (active_[f]) fields.push_back(uint32_t(f));
    return fields;
}

std::vector<gpu::PlantDynamic> InteractionWorld::initialDynamics() const {
    std::vector<gpu::PlantDynamic> dynamics;
    dynamics.reserve(plantCount_);
    for (const FieldVegetation& field : tile_->fields)
        dynamics.insert(dynamics.end(), field.dynamicRecords.begin(), field.dynamicRecords.end());
    return dynamics;
}

void InteractionWorld::saveState(const std::string& path, std::span<const gpu::PlantDynamic> dynamics,
                                 const TrackBlocks& tracks) const {
    require(dynamics.size() == plantCount_,
            path + ": cannot save the interaction state: " + std::to_string(dynamics.size()) +
                " dynamic records given, the tile has " + std::to_string(plantCount_) + " plants");
    InteractionState state{.tick = tick_,
                           .fieldActive = active_,
                           .lastContactTick = lastContact_,
                           .dynamics = {dynamics.begin(), dynamics.end()},
                           .tracks = tracks};
    saveInteractionState(path, state);
}

InteractionState InteractionWorld::restoreState(const std::string& path) {
    InteractionState state = loadInteractionState(path);
    require(state.fieldActive.size() == active_.size() && state.dynamics.size() == plantCount_,
            path + ": the interaction state belongs to another tile (" + std::to_string(state.fieldActive.size()) +
                " fields, " + std::to_string(state.dynamics.size()) + " plants; this tile has " +
                std::to_string(active_.size()) + " fields, " + std::to_string(plantCount_) + " plants)");
    tick_ = state.tick;
    active_ = std::move(state.fieldActive);
    lastContact_ = std::move(state.lastContactTick);
    return state;
}

void simulateOnCpu(std::vector<gpu::PlantDynamic>& dynamics, const TickResult& result,
                   const std::vector<uint32_t>& activeFields, const VegetationTile& tile,
                   const RecoveryParams& params) {
    for (TickContacts::Run run : result.contacts.runs())
        for (const gpu::PlantContact& contact : run) {
            assert(contact.plant < dynamics.size());
            dynamics[contact.plant] = applyContact(dynamics[contact.plant], contact, params);
        }
    for (uint32_t f : activeFields) {
        const FieldVegetation& field = tile.fields[f];
        assert(field.firstPlant + field.plantCount() <= dynamics.size());
        for (uint32_t i = field.firstPlant; i < field.firstPlant + field.plantCount(); ++i)
            dynamics[i] = recoverStep(dynamics[i], params);
    }
}

} // namespace sward

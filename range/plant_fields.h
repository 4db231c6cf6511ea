// The plants of a tile as Embree scenes (internal to range/: RayScene instances them), one per 25 m field.
//
// A field whose plants all rest (only the wind moves them) keeps a BVH over boxes that hold each plant under any tip
// the scene's wind gives (restingBounds), built once, and computes a plant's quads only when a ray first reaches its
// box in a tick: an atomic stamp per plant lets one thread compute them while others wait, and the values are pure
// functions, so the order does not matter. A touched field (a bent, felled or cut plant) gets all its quads and a BVH
// over their exact boxes every tick. Fields beyond the sensors' reach are dropped.
#pragma once

#include "range/plant_quads.h"

#include <embree3/rtcore.h>

#include <atomic>
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace sward {

class PlantFields {
public:
    // `tile`, `vegetation` and `atlas` must outlive the fields; `device` builds on one thread. `nearBlades`:
    // lod.near_blades (bladesOf).
    PlantFields(RTCDevice device, const VegetationTile& tile, const VegetationParams& vegetation,
                const AtlasAlpha& atlas, uint32_t nearBlades = 0);
    ~PlantFields();
    PlantFields(const PlantFields&) = delete;
    PlantFields& operator=(const PlantFields&) = delete;

    // The plants at simulation time `time` in the state `dynamics` (the tile's records in tile order; empty: its own):
    // every field whose box lies within `reach` metres of `centre` (xy) made ready for rays. The span must stay valid
    // until the next call.
    void setTick(const WindParams& wind, double time, std::span<const gpu::PlantDynamic> dynamics, glm::dvec2 centre,
                 double reach, uint32_t threads);
    // Each field in reach: its scene and its index, in field order.
    void forEachInReach(const std::function<void(RTCScene, uint32_t)>& visit) const;
    // The truth label of plant `plant` of field `field`, hit in this tick.
    uint32_t label(uint32_t field, uint32_t plant) const { return fields_[field].quads[plant].label; }
    uint64_t prepared() const { return prepared_.load(); } // plants whose quads this tick computed so far

private:
    struct Field {
        PlantFields* owner = nullptr;
        uint32_t index = 0, firstPlant = 0;
        RTCScene resting = nullptr, touched = nullptr;
        bool inReach = false, isTouched = false;
        std::vector<glm::vec3> restLo, restHi; // the resting BVH's boxes
        std::vector<UnbentPlant> unbent;       // resting plants' quads before the wind
        std::vector<PlantQuads> quads;
        std::unique_ptr<std::atomic<uint32_t>[]> stamps;
    };

    static void restingBoundsOf(const RTCBoundsFunctionArguments* args);
    static void touchedBoundsOf(const RTCBoundsFunctionArguments* args);
    static void intersect(const RTCIntersectFunctionNArguments* args);
    static void occluded(const RTCOccludedFunctionNArguments*) {} // rtcOccluded1 is not used

    const gpu::PlantDynamic& dynamicOf(const Field& f, uint32_t i) const;
    uint32_t bladesOf(const Field& f, uint32_t i) const; // the plant's blades (0: quads)
    const PlantQuads& current(Field& f, uint32_t i);
    RTCScene plantScene(Field& f, RTCBoundsFunction bounds);
    bool touchedNow(const Field& f) const;
    void prepare(Field& f);
    void dropResting(Field& f);

    RTCDevice device_;
    const VegetationTile& tile_;
    const VegetationParams& vegetation_;
    const AtlasAlpha& atlas_;
    uint32_t nearBlades_ = 0;
    std::vector<Field> fields_;
    WindTipRange windRange_{};
    // The tick's state, read by the intersector while rays are cast.
    WindParams wind_;
    double time_ = 0.0;
    std::span<const gpu::PlantDynamic> dynamics_;
    uint32_t stamp_ = 0; // ticks so far: a plant's quads are current when its stamp equals this
    std::atomic<uint64_t> prepared_{0};
};

} // namespace sward

#include "range/plant_fields.h"

#include "common/error.h"
#include "common/parallel_for.h"
#include "scene/range_sensors.h"

#include <thread>

namespace sward {

namespace {

constexpr uint32_t kBusy = 0xffffffffu; // a plant's stamp while one thread computes its quads

} // namespace

PlantFields::PlantFields(RTCDevice device, const VegetationTile& tile, const VegetationParams& vegetation,
                         const AtlasAlpha& atlas, uint32_t nearBlades)
    : device_(device), tile_(tile), vegetation_(vegetation), atlas_(atlas), nearBlades_(nearBlades),
      fields_(tile.fields.size()) {
    uint32_t first = 0;
    for (uint32_t f = 0; f < fields_.size(); ++f) {
        fields_[f].owner = this, fields_[f].index = f, fields_[f].firstPlant = first;
        first += tile.fields[f].plantCount();
    }
}

PlantFields::~PlantFields() {
    for (Field& f : fields_)
        for (RTCScene s : {f.resting, f.touched})
            if (s) rtcReleaseScene(s);
}

const gpu::PlantDynamic& PlantFields::dynamicOf(const Field& f, uint32_t i) const {
    return dynamics_.empty() ? tile_.fields[f.index].dynamicRecords[i] : dynamics_[f.firstPlant + i];
}

uint32_t PlantFields::bladesOf(const Field& f, uint32_t i) const {
    return sward::bladesOf(vegetation_, nearBlades_, tile_.fields[f.index].staticRecords[i].attributes & 3u);
}

// Plant i's quads of this tick, computed by the first thread that needs them (the others wait for it).
const PlantQuads& PlantFields::current(Field& f, uint32_t i) {
    std::atomic<uint32_t>& s = f.stamps[i];
    for (uint32_t seen = s.load(std::memory_order_acquire); seen != stamp_; seen = s.load(std::memory_order_acquire)) {
        if (seen != kBusy && s.compare_exchange_strong(seen, kBusy, std::memory_order_acquire)) {
            f.quads[i] = plantQuads(atlas_, vegetation_, wind_, tile_.fields[f.index], i, f.firstPlant + i,
                                    dynamicOf(f, i), time_, &f.unbent[i], bladesOf(f, i));
            prepared_.fetch_add(1, std::memory_order_relaxed);
            s.store(stamp_, std::memory_order_release);
            break;
        }
        std::this_thread::yield();
    }
    return f.quads[i];
}

void PlantFields::restingBoundsOf(const RTCBoundsFunctionArguments* args) {
    const Field& f = *static_cast<const Field*>(args->geometryUserPtr);
    const glm::vec3 lo = f.restLo[args->primID], hi = f.restHi[args->primID];
    *args->bounds_o = {lo.x, lo.y, lo.z, 0.0f, hi.x, hi.y, hi.z, 0.0f};
}

void PlantFields::touchedBoundsOf(const RTCBoundsFunctionArguments* args) {
    const PlantQuads& p = static_cast<const Field*>(args->geometryUserPtr)->quads[args->primID];
    *args->bounds_o = {p.lo.x, p.lo.y, p.lo.z, 0.0f, p.hi.x, p.hi.y, p.hi.z, 0.0f};
}

void PlantFields::intersect(const RTCIntersectFunctionNArguments* args) {
    const unsigned n = args->N; // 1 for rtcIntersect1, up to 8 for RayScene::cast8's packets
    RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, n);
    RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, n);
    Field& f = *static_cast<Field*>(args->geometryUserPtr);
    const PlantQuads* p = nullptr;
    for (unsigned i = 0; i < n; ++i) {
        if (!args->valid[i]) continue;
        if (!p) p = f.isTouched ? &f.quads[args->primID] : &f.owner->current(f, args->primID);
        const glm::vec3 o(RTCRayN_org_x(rays, n, i), RTCRayN_org_y(rays, n, i), RTCRayN_org_z(rays, n, i));
        const glm::vec3 d(RTCRayN_dir_x(rays, n, i), RTCRayN_dir_y(rays, n, i), RTCRayN_dir_z(rays, n, i));
        float best = RTCRayN_tfar(rays, n, i);
        glm::vec3 normal;
        if (!intersectPlant(*p, f.owner->atlas_, o, d, RTCRayN_tnear(rays, n, i), best, normal)) continue;
        RTCRayN_tfar(rays, n, i) = best;
        RTCHitN_Ng_x(hits, n, i) = normal.x, RTCHitN_Ng_y(hits, n, i) = normal.y, RTCHitN_Ng_z(hits, n, i) = normal.z;
        RTCHitN_u(hits, n, i) = RTCHitN_v(hits, n, i) = 0.0f;
        RTCHitN_primID(hits, n, i) = args->primID;
        RTCHitN_geomID(hits, n, i) = args->geomID;
        RTCHitN_instID(hits, n, i, 0) = args->context->instID[0];
    }
}

RTCScene PlantFields::plantScene(Field& f, RTCBoundsFunction bounds) {
    RTCScene scene = rtcNewScene(device_);
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, tile_.fields[f.index].plantCount());
    // A resting field's BVH serves every tick: worth Embree's best build.
    if (bounds == &PlantFields::restingBoundsOf) rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_HIGH);
    rtcSetGeometryUserData(geom, &f);
    rtcSetGeometryBoundsFunction(geom, bounds, nullptr);
    rtcSetGeometryIntersectFunction(geom, &PlantFields::intersect);
    rtcSetGeometryOccludedFunction(geom, &PlantFields::occluded);
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene, geom, 0);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
    const RTCError e = rtcGetDeviceError(device_);
    require(e == RTC_ERROR_NONE,
            "range sensors: Embree failed building a field of plants (error " + std::to_string(int(e)) + ")");
    return scene;
}

// Whether any plant of the field is out of its resting geometry in this tick.
bool PlantFields::touchedNow(const Field& f) const {
    for (uint32_t i = 0; i < tile_.fields[f.index].plantCount(); ++i)
        if (!restingGeometry(dynamicOf(f, i))) return true;
    return false;
}

// A field in reach this tick: its storage, its mode, and (touched) all its quads.
void PlantFields::prepare(Field& f) {
    const FieldVegetation& field = tile_.fields[f.index];
    const uint32_t n = field.plantCount();
    if (f.quads.size() != n) {
        f.quads.assign(n, PlantQuads{});
        f.stamps = std::make_unique<std::atomic<uint32_t>[]>(n); // zero: no tick yet (stamps start at 1)
    }
    f.isTouched = touchedNow(f);
    if (f.isTouched) {
        for (uint32_t i = 0; i < n; ++i) {
            f.quads[i] = plantQuads(atlas_, vegetation_, wind_, field, i, f.firstPlant + i, dynamicOf(f, i), time_,
                                    nullptr, bladesOf(f, i));
            f.stamps[i].store(stamp_, std::memory_order_relaxed);
        }
        prepared_.fetch_add(n, std::memory_order_relaxed);
    } else if (f.restLo.empty()) {
        f.restLo.resize(n), f.restHi.resize(n), f.unbent.resize(n);
        for (uint32_t i = 0; i < n; ++i) {
            f.unbent[i] = unbentPlant(atlas_, vegetation_, field, i);
            restingBounds(atlas_, vegetation_, field, i, f.unbent[i], windRange_, f.restLo[i], f.restHi[i],
                          bladesOf(f, i));
        }
    }
}

void PlantFields::dropResting(Field& f) {
    f.restLo = {}, f.restHi = {}, f.unbent = {};
    if (f.resting) rtcReleaseScene(f.resting), f.resting = nullptr;
}

void PlantFields::setTick(const WindParams& wind, double time, std::span<const gpu::PlantDynamic> dynamics,
                          glm::dvec2 centre, double reach, uint32_t threads) {
    uint64_t plants = 0;
    for (const FieldVegetation& field : tile_.fields) plants += field.plantCount();
    require(dynamics.empty() || dynamics.size() == plants, "range sensors: the dynamic records are not the tile's");
    wind_ = wind, time_ = time, dynamics_ = dynamics, ++stamp_, prepared_ = 0;
    const WindTipRange range = windTipRange(wind);
    if (range.lo != windRange_.lo || range.hi != windRange_.hi || range.length != windRange_.length)
        for (Field& f : fields_) dropResting(f); // another wind: the resting boxes no longer hold
    windRange_ = range;
    std::vector<uint32_t> inReach;
    for (Field& f : fields_) {
        const FieldVegetation& field = tile_.fields[f.index];
        const glm::dvec2 lo(field.boundsMin), hi(field.boundsMax);
        const glm::dvec2 nearest =
            glm::clamp(centre, lo - kPlantLean, hi + kPlantLean); // plants lean out of the field's box
        f.inReach = field.plantCount() > 0 && glm::distance(nearest, centre) <= reach;
        if (f.inReach) {
            inReach.push_back(f.index);
        } else {
            f.quads = {}, f.stamps.reset();
            dropResting(f);
        }
    }
    parallelFor(uint32_t(inReach.size()), threads, [&](uint32_t k, uint32_t) { prepare(fields_[inReach[k]]); });
    for (uint32_t index : inReach) { // Embree builds on its one thread
        Field& f = fields_[index];
        if (f.touched) rtcReleaseScene(f.touched), f.touched = nullptr;
        if (f.isTouched)
            f.touched = plantScene(f, &PlantFields::touchedBoundsOf);
        else if (!f.resting)
            f.resting = plantScene(f, &PlantFields::restingBoundsOf);
    }
}

void PlantFields::forEachInReach(const std::function<void(RTCScene, uint32_t)>& visit) const {
    for (const Field& f : fields_)
        if (f.inReach) visit(f.isTouched ? f.touched : f.resting, f.index);
}

} // namespace sward

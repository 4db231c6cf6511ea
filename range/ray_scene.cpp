#include "range/ray_scene.h"

#include "common/error.h"
#include "common/parallel_for.h"
#include "range/plant_quads.h"
#include "vegetation/records.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <set>
#include <thread>

namespace sward {

namespace {

// Top-level instance ids: the ground, the objects, the rut patches, then one per field.
constexpr uint32_t kGroundInstance = 0, kObjectsInstance = 1, kPatchesInstance = 2, kFirstFieldInstance = 3;
constexpr float kBlockMetres = gpu::kTrackCell * float(gpu::kTrackBlockCells);
constexpr uint32_t kBusy = 0xffffffffu; // a plant's stamp while one thread computes its quads

RTCGeometry addTriangles(RTCDevice device, RTCScene scene, const std::vector<glm::vec3>& positions,
                         const std::vector<uint32_t>& indices, uint32_t geomID) {
    if (indices.empty()) return nullptr;
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), positions.size()));
    auto* i = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(uint32_t), indices.size() / 3));
    if (v && i) {
        std::memcpy(v, positions.data(), positions.size() * sizeof(glm::vec3));
        std::memcpy(i, indices.data(), indices.size() * sizeof(uint32_t));
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene, geom, geomID);
    rtcReleaseGeometry(geom);
    return geom;
}

void attachInstance(RTCDevice device, RTCScene top, RTCScene child, uint32_t id) {
    static const float identity[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    RTCGeometry inst = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(inst, child);
    rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, identity);
    rtcCommitGeometry(inst);
    rtcAttachGeometryByID(top, inst, id);
    rtcReleaseGeometry(inst);
}

// The drawn ground's triangles: render/ground_mesh.cpp's heightfield triangulation (cell (i, j) as (p00, p10, p11) and
// (p00, p11, p01)) or the mesh's own.
void groundTriangles(const Ground& ground, std::vector<glm::vec3>& positions, std::vector<uint32_t>& indices) {
    if (const Heightfield* h = ground.heightfield()) {
        for (uint32_t j = 0; j < h->rows(); ++j)
            for (uint32_t i = 0; i < h->columns(); ++i)
                positions.push_back(
                    glm::vec3(h->origin() + glm::vec2(float(i), float(j)) * h->spacing(), h->sample(i, j)));
        for (uint32_t j = 0; j + 1 < h->rows(); ++j)
            for (uint32_t i = 0; i + 1 < h->columns(); ++i) {
                const uint32_t p00 = j * h->columns() + i, p10 = p00 + 1, p01 = p00 + h->columns(), p11 = p01 + 1;
                indices.insert(indices.end(), {p00, p10, p11, p00, p11, p01});
            }
    } else if (const TriangleMesh* mesh = ground.mesh()) {
        positions = mesh->positions, indices = mesh->indices;
    }
}

} // namespace

struct RayScene::Impl {
    const VegetationTile* tile;
    const VegetationParams& vegetation;
    AtlasAlpha atlas;
    WindTipRange windRange{};
    RTCDevice device = nullptr;
    RTCScene groundScene = nullptr, objectScene = nullptr, patchScene = nullptr, top = nullptr;
    std::vector<uint32_t> objectLabels;
    std::set<std::pair<int32_t, int32_t>> patchedBlocks; // the coarse ground's holes
    std::vector<uint32_t> patchIndices;                  // the patches' triangles, for the rut at a hit
    std::vector<float> patchRuts;                        // per patch point

    // The plants' state of the current tick, read by the intersector while rays are cast.
    WindParams wind;
    double time = 0.0;
    std::span<const gpu::PlantDynamic> dynamics;
    uint32_t stamp = 0; // setPlants calls so far: a plant's quads are current when its stamp equals this
    std::atomic<uint64_t> prepared{0};

    // A field's plants: while all rest (only the wind moves them) a BVH over boxes that hold them under any wind,
    // built once, with each plant's quads computed when a ray first reaches its box; once touched (bent, felled, cut)
    // a BVH over the exact boxes of the tick, rebuilt with all its quads every tick.
    struct Field {
        Impl* impl = nullptr;
        uint32_t index = 0, firstPlant = 0;
        RTCScene resting = nullptr, touched = nullptr;
        bool inReach = false, isTouched = false;
        std::vector<glm::vec3> restLo, restHi; // the resting BVH's boxes
        std::vector<UnbentPlant> unbent;       // resting plants' quads before the wind
        std::vector<PlantQuads> quads;
        std::unique_ptr<std::atomic<uint32_t>[]> stamps;
    };
    std::vector<Field> fields;

    Impl(const Ground& ground, const Atlas& a, const VegetationParams& v, const VegetationTile* t)
        : tile(t), vegetation(v), atlas(a) {
        // One build thread: the BVHs (and so which of two equally near surfaces a ray meets first) are the same on
        // every machine and run.
        device = rtcNewDevice("threads=1,set_affinity=0");
        require(device != nullptr, "range sensors: Embree could not start (rtcNewDevice)");
        std::vector<glm::vec3> positions;
        std::vector<uint32_t> indices;
        groundTriangles(ground, positions, indices);
        groundScene = rtcNewScene(device);
        if (RTCGeometry geom = addTriangles(device, groundScene, positions, indices, 0)) {
            rtcSetGeometryUserData(geom, this);
            rtcSetGeometryIntersectFilterFunction(geom, &Impl::groundHole);
            rtcCommitGeometry(geom);
        }
        rtcCommitScene(groundScene);
        check("building the ground");
        if (tile) {
            fields.resize(tile->fields.size());
            uint32_t first = 0;
            for (uint32_t f = 0; f < fields.size(); ++f) {
                fields[f].impl = this, fields[f].index = f, fields[f].firstPlant = first;
                first += tile->fields[f].plantCount();
            }
        }
        setObjects({});
    }

    // The coarse ground has a hole over every block drawn as a rut patch (terrain_holes.frag).
    static void groundHole(const RTCFilterFunctionNArguments* args) {
        const Impl& impl = *static_cast<const Impl*>(args->geometryUserPtr);
        if (impl.patchedBlocks.empty() || args->valid[0] == 0) return;
        const float t = RTCRayN_tfar(args->ray, args->N, 0);
        const float x = RTCRayN_org_x(args->ray, args->N, 0) + t * RTCRayN_dir_x(args->ray, args->N, 0);
        const float y = RTCRayN_org_y(args->ray, args->N, 0) + t * RTCRayN_dir_y(args->ray, args->N, 0);
        const std::pair<int32_t, int32_t> block(int32_t(std::floor(x / kBlockMetres)),
                                                int32_t(std::floor(y / kBlockMetres)));
        if (impl.patchedBlocks.count(block)) args->valid[0] = 0;
    }

    void setGroundPatches(const std::vector<GroundPatch>& patches) {
        if (patchScene) rtcReleaseScene(patchScene);
        patchScene = rtcNewScene(device);
        patchedBlocks.clear(), patchIndices.clear(), patchRuts.clear();
        std::vector<glm::vec3> positions;
        constexpr uint32_t side = gpu::kTrackPatchVertices;
        for (const GroundPatch& patch : patches) {
            require(patch.points.size() == side * side, "range sensors: a rut patch of the wrong size");
            patchedBlocks.insert({patch.blockX, patch.blockY});
            const uint32_t first = uint32_t(positions.size());
            for (const glm::vec4& p : patch.points) positions.push_back(glm::vec3(p)), patchRuts.push_back(p.w);
            for (uint32_t v = 0; v + 1 < side; ++v)
                for (uint32_t u = 0; u + 1 < side; ++u) {
                    const uint32_t p00 = first + v * side + u, p10 = p00 + 1, p01 = p00 + side, p11 = p01 + 1;
                    patchIndices.insert(patchIndices.end(), {p00, p10, p11, p00, p11, p01});
                }
        }
        addTriangles(device, patchScene, positions, patchIndices, 0);
        rtcCommitScene(patchScene);
        check("building the rut patches");
        rebuildTop();
    }

    // truth.frag's rule: track where the rut, interpolated over the triangle, is at least kTrackLabelDepth deep.
    uint32_t patchLabel(uint32_t triangle, float u, float v) const {
        const uint32_t* p = &patchIndices[3 * size_t(triangle)];
        const float rut = patchRuts[p[0]] * (1.0f - u - v) + patchRuts[p[1]] * u + patchRuts[p[2]] * v;
        return (rut >= gpu::kTrackLabelDepth ? gpu::kSemanticTrack : gpu::kSemanticGround) << gpu::kInstanceBits;
    }

    ~Impl() {
        for (Field& f : fields)
            for (RTCScene s : {f.resting, f.touched})
                if (s) rtcReleaseScene(s);
        for (RTCScene s : {groundScene, objectScene, patchScene, top})
            if (s) rtcReleaseScene(s);
        rtcReleaseDevice(device);
    }

    void check(const char* what) const {
        const RTCError e = rtcGetDeviceError(device);
        require(e == RTC_ERROR_NONE,
                std::string("range sensors: Embree failed in ") + what + " (error " + std::to_string(int(e)) + ")");
    }

    void setObjects(const std::vector<PosedTriangles>& objects) {
        if (objectScene) rtcReleaseScene(objectScene);
        objectScene = rtcNewScene(device);
        objectLabels.clear();
        for (uint32_t k = 0; k < objects.size(); ++k) {
            addTriangles(device, objectScene, objects[k].positions, objects[k].indices, k);
            objectLabels.push_back(objects[k].label);
        }
        rtcCommitScene(objectScene);
        check("building the objects");
        rebuildTop();
    }

    // The top level: instances of the ground, the objects and the fields in reach (a function of this tick only).
    void rebuildTop() {
        if (top) rtcReleaseScene(top);
        top = rtcNewScene(device);
        attachInstance(device, top, groundScene, kGroundInstance);
        attachInstance(device, top, objectScene, kObjectsInstance);
        if (patchScene) attachInstance(device, top, patchScene, kPatchesInstance);
        for (const Field& f : fields)
            if (f.inReach)
                attachInstance(device, top, f.isTouched ? f.touched : f.resting, kFirstFieldInstance + f.index);
        rtcCommitScene(top);
        check("building the top level");
    }

    const gpu::PlantDynamic& dynamicOf(const Field& f, uint32_t i) const {
        return dynamics.empty() ? tile->fields[f.index].dynamicRecords[i] : dynamics[f.firstPlant + i];
    }

    // Plant i's quads of this tick, computed by the first thread that needs them (the others wait for it).
    const PlantQuads& current(Field& f, uint32_t i) {
        std::atomic<uint32_t>& s = f.stamps[i];
        for (uint32_t seen = s.load(std::memory_order_acquire); seen != stamp;
             seen = s.load(std::memory_order_acquire)) {
            if (seen != kBusy && s.compare_exchange_strong(seen, kBusy, std::memory_order_acquire)) {
                f.quads[i] = plantQuads(atlas, vegetation, wind, tile->fields[f.index], i, f.firstPlant + i,
                                        dynamicOf(f, i), time, &f.unbent[i]);
                prepared.fetch_add(1, std::memory_order_relaxed);
                s.store(stamp, std::memory_order_release);
                break;
            }
            std::this_thread::yield();
        }
        return f.quads[i];
    }

    static void restingBounds(const RTCBoundsFunctionArguments* args) {
        const Field& f = *static_cast<const Field*>(args->geometryUserPtr);
        const glm::vec3 lo = f.restLo[args->primID], hi = f.restHi[args->primID];
        *args->bounds_o = {lo.x, lo.y, lo.z, 0.0f, hi.x, hi.y, hi.z, 0.0f};
    }

    static void touchedBounds(const RTCBoundsFunctionArguments* args) {
        const PlantQuads& p = static_cast<const Field*>(args->geometryUserPtr)->quads[args->primID];
        *args->bounds_o = {p.lo.x, p.lo.y, p.lo.z, 0.0f, p.hi.x, p.hi.y, p.hi.z, 0.0f};
    }

    static void intersect(const RTCIntersectFunctionNArguments* args) {
        if (!args->valid[0]) return;
        Field& f = *static_cast<Field*>(args->geometryUserPtr);
        const PlantQuads& p = f.isTouched ? f.quads[args->primID] : f.impl->current(f, args->primID);
        RTCRayHit& rh = *reinterpret_cast<RTCRayHit*>(args->rayhit);
        const glm::vec3 o(rh.ray.org_x, rh.ray.org_y, rh.ray.org_z), d(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
        float best = rh.ray.tfar;
        glm::vec3 normal;
        if (!intersectPlant(p, f.impl->atlas, o, d, rh.ray.tnear, best, normal)) return;
        rh.ray.tfar = best;
        rh.hit.Ng_x = normal.x, rh.hit.Ng_y = normal.y, rh.hit.Ng_z = normal.z;
        rh.hit.u = rh.hit.v = 0.0f;
        rh.hit.primID = args->primID;
        rh.hit.geomID = args->geomID;
        rh.hit.instID[0] = args->context->instID[0];
    }

    static void occluded(const RTCOccludedFunctionNArguments*) {} // rtcOccluded1 is not used

    RTCScene plantScene(Field& f, RTCBoundsFunction bounds) {
        RTCScene scene = rtcNewScene(device);
        RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(geom, tile->fields[f.index].plantCount());
        // A resting field's BVH serves every tick: worth Embree's best build.
        if (bounds == &Impl::restingBounds) rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_HIGH);
        rtcSetGeometryUserData(geom, &f);
        rtcSetGeometryBoundsFunction(geom, bounds, nullptr);
        rtcSetGeometryIntersectFunction(geom, &Impl::intersect);
        rtcSetGeometryOccludedFunction(geom, &Impl::occluded);
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(scene, geom, 0);
        rtcReleaseGeometry(geom);
        rtcCommitScene(scene);
        check("building a field of plants");
        return scene;
    }

    // Whether any plant of the field is out of its resting geometry in this tick.
    bool touchedNow(const Field& f) const {
        for (uint32_t i = 0; i < tile->fields[f.index].plantCount(); ++i)
            if (!restingGeometry(dynamicOf(f, i))) return true;
        return false;
    }

    // A field in reach this tick: its storage, its mode, and (touched) all its quads.
    void prepare(Field& f) {
        const FieldVegetation& field = tile->fields[f.index];
        const uint32_t n = field.plantCount();
        if (f.quads.size() != n) {
            f.quads.assign(n, PlantQuads{});
            f.stamps = std::make_unique<std::atomic<uint32_t>[]>(n); // zero: no tick yet (stamps start at 1)
        }
        f.isTouched = touchedNow(f);
        if (f.isTouched) {
            for (uint32_t i = 0; i < n; ++i) {
                f.quads[i] = plantQuads(atlas, vegetation, wind, field, i, f.firstPlant + i, dynamicOf(f, i), time);
                f.stamps[i].store(stamp, std::memory_order_relaxed);
            }
            prepared.fetch_add(n, std::memory_order_relaxed);
        } else if (f.restLo.empty()) {
            f.restLo.resize(n), f.restHi.resize(n), f.unbent.resize(n);
            for (uint32_t i = 0; i < n; ++i) {
                f.unbent[i] = unbentPlant(atlas, vegetation, field, i);
                sward::restingBounds(atlas, vegetation, field, i, f.unbent[i], windRange, f.restLo[i], f.restHi[i]);
            }
        }
    }
};

RayScene::RayScene(const Ground& ground, const Atlas& atlas, const VegetationParams& vegetation,
                   const VegetationTile* tile)
    : impl_(std::make_unique<Impl>(ground, atlas, vegetation, tile)) {}

RayScene::~RayScene() = default;

void RayScene::setPlants(const WindParams& wind, double time, std::span<const gpu::PlantDynamic> dynamics,
                         glm::dvec2 centre, double reach, uint32_t threads) {
    Impl& impl = *impl_;
    if (!impl.tile) return;
    uint64_t plants = 0;
    for (const FieldVegetation& field : impl.tile->fields) plants += field.plantCount();
    require(dynamics.empty() || dynamics.size() == plants, "range sensors: the dynamic records are not the tile's");
    impl.wind = wind, impl.time = time, impl.dynamics = dynamics, ++impl.stamp;
    const WindTipRange range = windTipRange(wind);
    if (range.lo != impl.windRange.lo || range.hi != impl.windRange.hi || range.length != impl.windRange.length)
        for (Impl::Field& f : impl.fields) { // another wind: the resting boxes no longer hold
            f.restLo.clear(), f.restHi.clear(), f.unbent.clear();
            if (f.resting) rtcReleaseScene(f.resting), f.resting = nullptr;
        }
    impl.windRange = range;
    impl.prepared = 0;
    std::vector<uint32_t> inReach;
    for (Impl::Field& f : impl.fields) {
        const FieldVegetation& field = impl.tile->fields[f.index];
        const glm::dvec2 lo(field.boundsMin), hi(field.boundsMax);
        const glm::dvec2 nearest = glm::clamp(centre, lo - 2.0, hi + 2.0); // plants lean out of the field's box
        f.inReach = field.plantCount() > 0 && glm::distance(nearest, centre) <= reach;
        if (f.inReach) {
            inReach.push_back(f.index);
        } else {
            f.quads = {}, f.stamps.reset(), f.unbent = {}, f.restLo = {}, f.restHi = {};
            if (f.resting) rtcReleaseScene(f.resting), f.resting = nullptr;
        }
    }
    parallelFor(uint32_t(inReach.size()), threads,
                [&](uint32_t k, uint32_t) { impl.prepare(impl.fields[inReach[k]]); });
    for (uint32_t index : inReach) { // Embree builds on its one thread
        Impl::Field& f = impl.fields[index];
        if (f.touched) rtcReleaseScene(f.touched), f.touched = nullptr;
        if (f.isTouched)
            f.touched = impl.plantScene(f, &Impl::touchedBounds);
        else if (!f.resting)
            f.resting = impl.plantScene(f, &Impl::restingBounds);
    }
    impl.rebuildTop();
}

void RayScene::setObjects(const std::vector<PosedTriangles>& objects) {
    impl_->setObjects(objects);
}

void RayScene::setGroundPatches(const std::vector<GroundPatch>& patches) {
    impl_->setGroundPatches(patches);
}

uint64_t RayScene::plantsPrepared() const {
    return impl_->prepared.load();
}

RangeHit RayScene::cast(glm::dvec3 origin, glm::dvec3 direction, double tNear, double tFar) const {
    const Impl& impl = *impl_;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = float(origin.x), rh.ray.org_y = float(origin.y), rh.ray.org_z = float(origin.z);
    rh.ray.dir_x = float(direction.x), rh.ray.dir_y = float(direction.y), rh.ray.dir_z = float(direction.z);
    rh.ray.tnear = float(tNear), rh.ray.tfar = float(tFar);
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl.top, &context, &rh);
    RangeHit out;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return out;
    out.distance = rh.ray.tfar;
    const uint32_t instance = rh.hit.instID[0];
    if (instance == kGroundInstance)
        out.label = gpu::kSemanticGround << gpu::kInstanceBits;
    else if (instance == kObjectsInstance)
        out.label = impl.objectLabels[rh.hit.geomID];
    else if (instance == kPatchesInstance)
        out.label = impl.patchLabel(rh.hit.primID, rh.hit.u, rh.hit.v);
    else
        out.label = impl.fields[instance - kFirstFieldInstance].quads[rh.hit.primID].label;
    glm::vec3 n = glm::normalize(glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
    if (glm::dot(glm::dvec3(n), direction) > 0.0) n = -n;
    out.normal = n;
    return out;
}

} // namespace sward

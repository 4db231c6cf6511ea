#include "range/ray_scene.h"

#include "common/error.h"
#include "common/parallel_for.h"
#include "vegetation/expansion_reference.h"
#include "vegetation/records.h"

#include <embree3/rtcore.h>
#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace sward {

namespace {

// Top-level instance ids: the ground, the objects, then one per field.
constexpr uint32_t kGroundInstance = 0, kObjectsInstance = 1, kFirstFieldInstance = 2;
constexpr uint32_t kNearQuads = gpu::kQuadsNear;

// One plant's near quads at the current tick.
struct PlantQuads {
    glm::vec3 corners[4 * kNearQuads]; // per quad (0,0), (1,0), (1,1), (0,1): triangles (0,1,2), (0,2,3)
    glm::vec3 lo, hi;                  // their bounding box
    uint32_t cell = 0;                 // atlas cell (category * maxColumns + variant)
    float cutFraction = 1.0f;          // the part of the cell shown (cut plants show their lower part)
    uint32_t label = 0;
    bool mirrored = false, present = false;
};

struct AtlasAlpha {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> alpha;         // level 0
    std::vector<glm::vec4> uvRects;     // per cell
    std::vector<glm::vec3> baseAspects; // per cell: base u, base v, aspect
    uint32_t maxColumns = 1;
    std::array<uint32_t, 4> columns{};

    // Bilinear alpha at uv, clamp to edge, texel centres at +0.5 (the GPU sampler's rule at level 0).
    float sample(glm::vec2 uv) const {
        const float x = uv.x * float(width) - 0.5f, y = uv.y * float(height) - 0.5f;
        const float fx0 = std::floor(x), fy0 = std::floor(y);
        const float fx = x - fx0, fy = y - fy0;
        auto at = [&](float i, float j) {
            const int64_t ii = std::clamp<int64_t>(int64_t(i), 0, int64_t(width) - 1);
            const int64_t jj = std::clamp<int64_t>(int64_t(j), 0, int64_t(height) - 1);
            return float(alpha[size_t(jj) * width + size_t(ii)]) * (1.0f / 255.0f);
        };
        const float top = at(fx0, fy0) * (1.0f - fx) + at(fx0 + 1.0f, fy0) * fx;
        const float bottom = at(fx0, fy0 + 1.0f) * (1.0f - fx) + at(fx0 + 1.0f, fy0 + 1.0f) * fx;
        return top * (1.0f - fy) + bottom * fy;
    }
};

AtlasAlpha atlasAlpha(const Atlas& atlas) {
    require(!atlas.mips.empty(), "range sensors: the atlas has no image");
    AtlasAlpha a;
    const AtlasMip& mip = atlas.mips[0];
    a.width = mip.width, a.height = mip.height;
    a.alpha.resize(size_t(mip.width) * mip.height);
    for (size_t i = 0; i < a.alpha.size(); ++i) a.alpha[i] = mip.rgba[4 * i + 3];
    const AtlasDesc& desc = atlas.desc;
    a.maxColumns = desc.maxColumns();
    a.uvRects.resize(desc.rows.size() * a.maxColumns, glm::vec4(0.0f));
    a.baseAspects.resize(a.uvRects.size(), glm::vec3(0.5f, 1.0f, 1.0f));
    for (uint32_t r = 0; r < desc.rows.size(); ++r) {
        if (r < 4) a.columns[r] = uint32_t(desc.rows[r].cells.size());
        for (uint32_t c = 0; c < desc.rows[r].cells.size(); ++c) {
            const auto uv = desc.cellUvRect(r, c);
            const AtlasCell& cell = desc.rows[r].cells[c];
            a.uvRects[r * a.maxColumns + c] = glm::vec4(uv[0], uv[1], uv[2], uv[3]);
            a.baseAspects[r * a.maxColumns + c] = glm::vec3(cell.baseU, cell.baseV, cell.aspect);
        }
    }
    return a;
}

// plant_vertex.glsl's cell choice.
uint32_t plantCell(const AtlasAlpha& atlas, uint32_t attributes) {
    const uint32_t category = attributes & 3u, variant = (attributes >> 2) & 63u;
    return category * atlas.maxColumns + variant % std::max(atlas.columns[category], 1u);
}

// plant.vert's truth label of a plant.
uint32_t plantLabel(const gpu::ExpandedPlant& plant, uint32_t plantInTile) {
    const uint32_t state = (plant.fade >> 17) & 0xfu;
    const uint32_t semantic = state == gpu::kPlantStateFelled ? gpu::kSemanticFelled
                              : state == gpu::kPlantStateCut  ? gpu::kSemanticCut
                                                              : gpu::kSemanticVegetation + (plant.attributes & 3u);
    return (semantic << gpu::kInstanceBits) | (plantInTile + 1u);
}

// Ray / triangle (Moller-Trumbore, two-sided): distance and barycentrics of p1, p2.
bool intersectTriangle(glm::vec3 o, glm::vec3 d, glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, float& t, float& b1,
                       float& b2) {
    const glm::vec3 e1 = p1 - p0, e2 = p2 - p0, p = glm::cross(d, e2);
    const float det = glm::dot(e1, p);
    if (std::abs(det) < 1e-20f) return false;
    const float inv = 1.0f / det;
    const glm::vec3 s = o - p0;
    b1 = glm::dot(s, p) * inv;
    if (b1 < 0.0f || b1 > 1.0f) return false;
    const glm::vec3 q = glm::cross(s, e1);
    b2 = glm::dot(d, q) * inv;
    if (b2 < 0.0f || b1 + b2 > 1.0f) return false;
    t = glm::dot(e2, q) * inv;
    return true;
}

bool rayHitsBox(glm::vec3 o, glm::vec3 inv, glm::vec3 lo, glm::vec3 hi, float tNear, float tFar) {
    const glm::vec3 a = (lo - o) * inv, b = (hi - o) * inv;
    const glm::vec3 mn = glm::min(a, b), mx = glm::max(a, b);
    const float enter = std::max({mn.x, mn.y, mn.z, tNear}), leave = std::min({mx.x, mx.y, mx.z, tFar});
    return enter <= leave;
}

} // namespace

struct RayScene::Impl {
    const Ground& ground;
    const VegetationParams& vegetation;
    const VegetationTile* tile;
    AtlasAlpha atlas;
    RTCDevice device = nullptr;
    RTCScene groundScene = nullptr, objectScene = nullptr, top = nullptr;
    std::vector<uint32_t> objectLabels;

    struct Field {
        Impl* impl = nullptr;
        uint32_t index = 0, firstPlant = 0;
        RTCScene scene = nullptr; // built on first use
        std::vector<PlantQuads> quads;
        bool inReach = false;
    };
    std::vector<Field> fields;
    uint64_t prepared = 0;

    Impl(const Ground& g, const Atlas& a, const VegetationParams& v, const VegetationTile* t)
        : ground(g), vegetation(v), tile(t), atlas(atlasAlpha(a)) {
        // One build thread: the BVHs (and so which of two equally near surfaces a ray meets first) are the same on
        // every machine and run.
        device = rtcNewDevice("threads=1,set_affinity=0");
        require(device != nullptr, "range sensors: Embree could not start (rtcNewDevice)");
        buildGround();
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

    ~Impl() {
        for (Field& f : fields)
            if (f.scene) rtcReleaseScene(f.scene);
        for (RTCScene s : {groundScene, objectScene, top})
            if (s) rtcReleaseScene(s);
        rtcReleaseDevice(device);
    }

    void check(const char* what) const {
        const RTCError e = rtcGetDeviceError(device);
        require(e == RTC_ERROR_NONE, std::string("range sensors: Embree failed in ") + what + " (error " +
                                         std::to_string(int(e)) + ")");
    }

    static void addTriangles(RTCDevice device, RTCScene scene, const std::vector<glm::vec3>& positions,
                             const std::vector<uint32_t>& indices, uint32_t geomID) {
        if (indices.empty()) return;
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
    }

    void buildGround() {
        std::vector<glm::vec3> positions;
        std::vector<uint32_t> indices;
        if (const Heightfield* h = ground.heightfield()) {
            // render/ground_mesh.cpp's triangulation: cell (i, j) as (p00, p10, p11) and (p00, p11, p01).
            for (uint32_t j = 0; j < h->rows(); ++j)
                for (uint32_t i = 0; i < h->columns(); ++i)
                    positions.push_back(glm::vec3(h->origin() + glm::vec2(float(i), float(j)) * h->spacing(), h->sample(i, j)));
            for (uint32_t j = 0; j + 1 < h->rows(); ++j)
                for (uint32_t i = 0; i + 1 < h->columns(); ++i) {
                    const uint32_t p00 = j * h->columns() + i, p10 = p00 + 1, p01 = p00 + h->columns(), p11 = p01 + 1;
                    indices.insert(indices.end(), {p00, p10, p11, p00, p11, p01});
                }
        } else if (const TriangleMesh* mesh = ground.mesh()) {
            positions = mesh->positions, indices = mesh->indices;
        }
        groundScene = rtcNewScene(device);
        addTriangles(device, groundScene, positions, indices, 0);
        rtcCommitScene(groundScene);
        check("building the ground");
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

    static void attachInstance(RTCDevice device, RTCScene top, RTCScene child, uint32_t id) {
        static const float identity[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
        RTCGeometry inst = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(inst, child);
        rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, identity);
        rtcCommitGeometry(inst);
        rtcAttachGeometryByID(top, inst, id);
        rtcReleaseGeometry(inst);
    }

    // The top level: instances of the ground, the objects and the fields in reach (a function of this tick only).
    void rebuildTop() {
        if (top) rtcReleaseScene(top);
        top = rtcNewScene(device);
        attachInstance(device, top, groundScene, kGroundInstance);
        attachInstance(device, top, objectScene, kObjectsInstance);
        for (const Field& f : fields)
            if (f.inReach) attachInstance(device, top, f.scene, kFirstFieldInstance + f.index);
        rtcCommitScene(top);
        check("building the top level");
    }

    // The box every state of plant i can occupy (any wind, bend, fall or cut): its base plus the reach of its cell.
    static void plantBounds(const struct RTCBoundsFunctionArguments* args) {
        const Field& f = *static_cast<const Field*>(args->geometryUserPtr);
        const Impl& impl = *f.impl;
        const FieldVegetation& field = impl.tile->fields[f.index];
        const gpu::PlantStatic& plant = field.staticRecords[args->primID];
        const PlantInstance decoded = decodePlantStatic(plant);
        const glm::vec3 base = decodePlantPosition(plant, field.origin, field.positionStep);
        const float h = impl.vegetation.categories[decoded.category].height * (float(decoded.size) / gpu::kPlantSizeDivisor);
        const glm::vec3 cell = impl.atlas.baseAspects[plantCell(impl.atlas, plant.attributes)];
        const float bu = std::max(cell.x, 1.0f - cell.x), bv = std::max(cell.y, 1.0f - cell.y);
        const float below = cell.y > 0.0f ? (1.0f - cell.y) / cell.y : 0.0f;
        const float bend = std::max(1.0f, below * below); // quadPoint's fraction^2 at the cell's far edge
        const float r = 1.01f * (h * cell.z * bu + h * bv + bend * (gpu::kMaxTipOffset + 1.0f) * h) + 1e-3f;
        *args->bounds_o = {base.x - r, base.y - r, base.z - r, 0.0f, base.x + r, base.y + r, base.z + r, 0.0f};
    }

    static void plantIntersect(const RTCIntersectFunctionNArguments* args) {
        if (!args->valid[0]) return;
        const Field& f = *static_cast<const Field*>(args->geometryUserPtr);
        const PlantQuads& p = f.quads[args->primID];
        if (!p.present) return;
        RTCRayHit& rh = *reinterpret_cast<RTCRayHit*>(args->rayhit);
        const glm::vec3 o(rh.ray.org_x, rh.ray.org_y, rh.ray.org_z), d(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
        if (!rayHitsBox(o, 1.0f / d, p.lo, p.hi, rh.ray.tnear, rh.ray.tfar)) return;
        const AtlasAlpha& atlas = f.impl->atlas;
        const glm::vec4 rect = atlas.uvRects[p.cell];
        static const glm::vec2 kQuadCorner[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        static const uint32_t kTriangle[2][3] = {{0, 1, 2}, {0, 2, 3}};
        float best = rh.ray.tfar;
        glm::vec3 normal(0.0f);
        for (uint32_t q = 0; q < kNearQuads; ++q)
            for (const auto& tri : kTriangle) {
                const glm::vec3 *c = &p.corners[4 * q], &p0 = c[tri[0]], &p1 = c[tri[1]], &p2 = c[tri[2]];
                float t, b1, b2;
                if (!intersectTriangle(o, d, p0, p1, p2, t, b1, b2) || t < rh.ray.tnear || !(t < best)) continue;
                // The texel the GPU would show there: uv interpolated over the triangle as plant_vertex.glsl sets it.
                const glm::vec2 corner = kQuadCorner[tri[0]] * (1.0f - b1 - b2) + kQuadCorner[tri[1]] * b1 +
                                         kQuadCorner[tri[2]] * b2;
                const glm::vec2 cellUv(p.mirrored ? 1.0f - corner.x : corner.x, 1.0f - corner.y * p.cutFraction);
                const glm::vec2 uv = glm::mix(glm::vec2(rect.x, rect.y), glm::vec2(rect.z, rect.w), cellUv);
                if (atlas.sample(uv) < 0.5f) continue;
                best = t;
                normal = glm::cross(p1 - p0, p2 - p0);
            }
        if (!(best < rh.ray.tfar)) return;
        rh.ray.tfar = best;
        rh.hit.Ng_x = normal.x, rh.hit.Ng_y = normal.y, rh.hit.Ng_z = normal.z;
        rh.hit.u = rh.hit.v = 0.0f;
        rh.hit.primID = args->primID;
        rh.hit.geomID = args->geomID;
        rh.hit.instID[0] = args->context->instID[0];
    }

    static void plantOccluded(const RTCOccludedFunctionNArguments*) {} // rtcOccluded1 is not used

    void buildField(Field& f) {
        const FieldVegetation& field = tile->fields[f.index];
        f.scene = rtcNewScene(device);
        RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(geom, field.plantCount());
        rtcSetGeometryUserData(geom, &f);
        rtcSetGeometryBoundsFunction(geom, &Impl::plantBounds, nullptr);
        rtcSetGeometryIntersectFunction(geom, &Impl::plantIntersect);
        rtcSetGeometryOccludedFunction(geom, &Impl::plantOccluded);
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(f.scene, geom, 0);
        rtcReleaseGeometry(geom);
        rtcCommitScene(f.scene);
        check("building a field of plants");
    }

    void prepareField(Field& f, const WindParams& wind, double time, std::span<const gpu::PlantDynamic> dynamics) {
        const FieldVegetation& field = tile->fields[f.index];
        f.quads.resize(field.plantCount());
        for (uint32_t i = 0; i < field.plantCount(); ++i) {
            PlantQuads& p = f.quads[i];
            const gpu::PlantDynamic& dynamic = dynamics.empty() ? field.dynamicRecords[i] : dynamics[f.firstPlant + i];
            const gpu::ExpandedPlant plant = expandWholePlant(vegetation, wind, field, i, dynamic, time);
            p.cell = plantCell(atlas, plant.attributes);
            p.cutFraction = float(plant.fade >> 24) * (1.0f / 255.0f);
            p.mirrored = float((plant.attributes >> 16) & 0xffu) * (1.0f / 255.0f) > 0.5f;
            p.label = plantLabel(plant, f.firstPlant + i);
            p.present = plant.positionHeight.w > 0.0f;
            plantQuadCorners(plant, gpu::kLodNear, glm::vec3(0.0f), atlas.baseAspects[p.cell], p.corners);
            p.lo = p.hi = p.corners[0];
            for (const glm::vec3& c : p.corners) p.lo = glm::min(p.lo, c), p.hi = glm::max(p.hi, c);
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
    std::vector<uint32_t> inReach;
    for (Impl::Field& f : impl.fields) {
        const FieldVegetation& field = impl.tile->fields[f.index];
        const glm::dvec2 lo(field.boundsMin), hi(field.boundsMax);
        const glm::dvec2 nearest = glm::clamp(centre, lo - 2.0, hi + 2.0); // plants lean out of the field's box
        f.inReach = field.plantCount() > 0 && glm::distance(nearest, centre) <= reach;
        if (f.inReach) inReach.push_back(f.index);
        else f.quads = {};
    }
    for (uint32_t index : inReach)
        if (!impl.fields[index].scene) impl.buildField(impl.fields[index]); // Embree builds on its one thread
    parallelFor(uint32_t(inReach.size()), threads,
                [&](uint32_t k, uint32_t) { impl.prepareField(impl.fields[inReach[k]], wind, time, dynamics); });
    impl.prepared = 0;
    for (uint32_t index : inReach) impl.prepared += impl.fields[index].quads.size();
    impl.rebuildTop();
}

void RayScene::setObjects(const std::vector<PosedTriangles>& objects) {
    impl_->setObjects(objects);
}

uint64_t RayScene::plantsPrepared() const {
    return impl_->prepared;
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
    if (instance == kGroundInstance) out.label = gpu::kSemanticGround << gpu::kInstanceBits;
    else if (instance == kObjectsInstance) out.label = impl.objectLabels[rh.hit.geomID];
    else out.label = impl.fields[instance - kFirstFieldInstance].quads[rh.hit.primID].label;
    glm::vec3 n = glm::normalize(glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
    if (glm::dot(glm::dvec3(n), direction) > 0.0) n = -n;
    out.normal = n;
    return out;
}

} // namespace sward

#include "range/ray_scene.h"

#include "common/error.h"
#include "range/plant_fields.h"
#include "world/heightfield_mesh.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>

namespace sward {

namespace {

// Top-level instance ids: the ground, the objects, the rut patches, then one per field.
constexpr uint32_t kGroundInstance = 0, kObjectsInstance = 1, kPatchesInstance = 2, kFirstFieldInstance = 3;
constexpr float kBlockMetres = gpu::kTrackCell * float(gpu::kTrackBlockCells);

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

// The drawn ground's triangles: the heightfield's drawn triangulation (world/heightfield_mesh.h) or the mesh's own.
void groundTriangles(const Ground& ground, std::vector<glm::vec3>& positions, std::vector<uint32_t>& indices) {
    if (const Heightfield* h = ground.heightfield()) {
        for (uint32_t j = 0; j < h->rows(); ++j)
            for (uint32_t i = 0; i < h->columns(); ++i) positions.push_back(heightfieldVertex(*h, i, j));
        indices = heightfieldTriangleIndices(*h);
    } else if (const TriangleMesh* mesh = ground.mesh()) {
        positions = mesh->positions, indices = mesh->indices;
    }
}

} // namespace

struct RayScene::Impl {
    // A tile's ground and plants: one for a one-tile scene, those setTiles gave in a world.
    struct Tile {
        RayTile source;
        RTCScene ground = nullptr;
        std::unique_ptr<PlantFields> plants; // null without vegetation
    };
    // What a top-level instance id holds (rebuildTop), for the label of a hit.
    struct Instance {
        enum class Kind { None, Ground, Objects, Patches, Field } kind = Kind::None;
        uint32_t tile = 0, field = 0;
    };

    AtlasAlpha atlas;
    const VegetationParams& vegetation;
    uint32_t nearBlades = 0;
    bool world = false;
    uint32_t tilesX = 1;
    RTCDevice device = nullptr;
    RTCScene objectScene = nullptr, patchScene = nullptr, top = nullptr;
    std::vector<Tile> tiles;
    std::vector<Instance> instances; // by top-level instance id
    std::vector<uint32_t> objectLabels;
    std::set<std::pair<int32_t, int32_t>> patchedBlocks; // the coarse ground's holes
    std::vector<uint32_t> patchIndices;                  // the patches' triangles, for the rut at a hit
    std::vector<float> patchRuts;                        // per patch point

    Impl(const Atlas& a, const VegetationParams& v, uint32_t blades, bool isWorld)
        : atlas(a), vegetation(v), nearBlades(blades), world(isWorld) {
        // One build thread: the BVHs (and so which of two equally near surfaces a ray meets first) are the same on
        // every machine and run.
        device = rtcNewDevice("threads=1,set_affinity=0");
        require(device != nullptr, "range sensors: Embree could not start (rtcNewDevice)");
    }

    Tile makeTile(const RayTile& source) {
        Tile tile{.source = source};
        std::vector<glm::vec3> positions;
        std::vector<uint32_t> indices;
        groundTriangles(*source.ground, positions, indices);
        tile.ground = rtcNewScene(device);
        if (RTCGeometry geom = addTriangles(device, tile.ground, positions, indices, 0)) {
            rtcSetGeometryUserData(geom, this);
            rtcSetGeometryIntersectFilterFunction(geom, &Impl::groundHole);
            rtcCommitGeometry(geom);
        }
        rtcCommitScene(tile.ground);
        check("building the ground");
        if (source.plants)
            tile.plants = std::make_unique<PlantFields>(device, *source.plants, vegetation, atlas, nearBlades);
        return tile;
    }

    void releaseTile(Tile& tile) {
        tile.plants.reset(); // its scenes first
        if (tile.ground) rtcReleaseScene(tile.ground), tile.ground = nullptr;
    }

    void setTiles(std::span<const RayTile> given) {
        require(world, "RayScene::setTiles: a one-tile scene has its tile");
        std::vector<Tile> next;
        size_t held = 0;
        for (const RayTile& t : given) {
            require(t.ground != nullptr, "RayScene::setTiles: a tile without ground");
            require(next.empty() || std::pair(next.back().source.coord.y, next.back().source.coord.x) <
                                        std::pair(t.coord.y, t.coord.x),
                    "RayScene::setTiles: tiles must ascend in (y, x)");
            // Both lists ascend: a held tile is found by walking them together.
            while (held < tiles.size() &&
                   std::pair(tiles[held].source.coord.y, tiles[held].source.coord.x) < std::pair(t.coord.y, t.coord.x))
                releaseTile(tiles[held++]);
            Tile* same = held < tiles.size() && tiles[held].source.coord == t.coord ? &tiles[held] : nullptr;
            if (same && same->source.ground == t.ground && same->source.plants == t.plants) {
                next.push_back(std::move(*same)), same->ground = nullptr, ++held;
            } else {
                if (same) releaseTile(*same), ++held;
                next.push_back(makeTile(t));
            }
        }
        for (; held < tiles.size(); ++held) releaseTile(tiles[held]);
        tiles = std::move(next);
        rebuildTop();
    }

    // The coarse ground has a hole over every block drawn as a rut patch (terrain_holes.frag).
    static void groundHole(const RTCFilterFunctionNArguments* args) {
        const Impl& impl = *static_cast<const Impl*>(args->geometryUserPtr);
        if (impl.patchedBlocks.empty()) return;
        for (unsigned i = 0; i < args->N; ++i) {
            if (args->valid[i] == 0) continue;
            const float t = RTCRayN_tfar(args->ray, args->N, i);
            const float x = RTCRayN_org_x(args->ray, args->N, i) + t * RTCRayN_dir_x(args->ray, args->N, i);
            const float y = RTCRayN_org_y(args->ray, args->N, i) + t * RTCRayN_dir_y(args->ray, args->N, i);
            const std::pair<int32_t, int32_t> block(int32_t(std::floor(x / kBlockMetres)),
                                                    int32_t(std::floor(y / kBlockMetres)));
            if (impl.patchedBlocks.count(block)) args->valid[i] = 0;
        }
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

    RangeHit hitOf(const RTCRay& ray, const RTCHit& hit, glm::dvec3 direction) const;

    ~Impl() {
        for (Tile& tile : tiles) releaseTile(tile); // their scenes first, then the device
        for (RTCScene s : {objectScene, patchScene, top})
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
    // A one-tile scene: its ground 0, the objects 1, the rut patches 2, field f at 3 + f. A world: the objects and
    // patches the same, then each tile in order, its ground and its fields in reach, numbered on from 3.
    void rebuildTop() {
        if (top) rtcReleaseScene(top);
        top = rtcNewScene(device);
        instances.assign(kFirstFieldInstance, Instance{});
        auto attach = [&](RTCScene scene, uint32_t id, Instance what) {
            attachInstance(device, top, scene, id);
            if (instances.size() <= id) instances.resize(id + 1);
            instances[id] = what;
        };
        if (!world) attach(tiles[0].ground, kGroundInstance, {Instance::Kind::Ground, 0, 0});
        attach(objectScene, kObjectsInstance, {Instance::Kind::Objects, 0, 0});
        if (patchScene) attach(patchScene, kPatchesInstance, {Instance::Kind::Patches, 0, 0});
        uint32_t next = kFirstFieldInstance;
        for (uint32_t t = 0; t < tiles.size(); ++t) {
            if (world) attach(tiles[t].ground, next++, {Instance::Kind::Ground, t, 0});
            if (tiles[t].plants)
                tiles[t].plants->forEachInReach([&](RTCScene field, uint32_t index) {
                    attach(field, world ? next++ : kFirstFieldInstance + index, {Instance::Kind::Field, t, index});
                });
        }
        rtcCommitScene(top);
        check("building the top level");
    }
};

RayScene::RayScene(const Ground& ground, const Atlas& atlas, const VegetationParams& vegetation,
                   const VegetationTile* tile, uint32_t nearBlades)
    : impl_(std::make_unique<Impl>(atlas, vegetation, nearBlades, false)) {
    impl_->tiles.push_back(impl_->makeTile({TileCoord{}, &ground, tile}));
    impl_->setObjects({});
}

RayScene::RayScene(const Atlas& atlas, const VegetationParams& vegetation, uint32_t tilesX, uint32_t nearBlades)
    : impl_(std::make_unique<Impl>(atlas, vegetation, nearBlades, true)) {
    impl_->tilesX = tilesX;
    impl_->setObjects({});
}

RayScene::~RayScene() = default;

void RayScene::setTiles(std::span<const RayTile> tiles) {
    impl_->setTiles(tiles);
}

void RayScene::setPlants(const WindParams& wind, double time, std::span<const gpu::PlantDynamic> dynamics,
                         glm::dvec2 centre, double reach, uint32_t threads) {
    require(!impl_->world || dynamics.empty(), "RayScene::setPlants: a world's tiles hold their own dynamic records");
    bool any = false;
    for (Impl::Tile& tile : impl_->tiles)
        if (tile.plants) tile.plants->setTick(wind, time, dynamics, centre, reach, threads), any = true;
    if (any) impl_->rebuildTop();
}

void RayScene::setObjects(const std::vector<PosedTriangles>& objects) {
    impl_->setObjects(objects);
}

void RayScene::setGroundPatches(const std::vector<GroundPatch>& patches) {
    impl_->setGroundPatches(patches);
}

uint64_t RayScene::plantsPrepared() const {
    uint64_t prepared = 0;
    for (const Impl::Tile& tile : impl_->tiles)
        if (tile.plants) prepared += tile.plants->prepared();
    return prepared;
}

// The hit of one ray as RangeHit: distance, the truth label of what it hit, the normal facing the ray.
RangeHit RayScene::Impl::hitOf(const RTCRay& ray, const RTCHit& hit, glm::dvec3 direction) const {
    RangeHit out;
    if (hit.geomID == RTC_INVALID_GEOMETRY_ID) return out;
    out.distance = ray.tfar;
    const Instance& instance = instances[hit.instID[0]];
    switch (instance.kind) {
    case Instance::Kind::Ground:
        out.label = gpu::kSemanticGround << gpu::kInstanceBits;
        break;
    case Instance::Kind::Objects:
        out.label = objectLabels[hit.geomID];
        break;
    case Instance::Kind::Patches:
        out.label = patchLabel(hit.primID, hit.u, hit.v);
        break;
    case Instance::Kind::Field:
        out.label = tiles[instance.tile].plants->label(instance.field, hit.primID);
        if (world) {
            const TileCoord coord = tiles[instance.tile].source.coord;
            out.tile = uint32_t(coord.y) * tilesX + uint32_t(coord.x) + 1;
        }
        break;
    case Instance::Kind::None:
        break;
    }
    glm::vec3 n = glm::normalize(glm::vec3(hit.Ng_x, hit.Ng_y, hit.Ng_z));
    if (glm::dot(glm::dvec3(n), direction) > 0.0) n = -n;
    out.normal = n;
    return out;
}

RangeHit RayScene::cast(glm::dvec3 origin, glm::dvec3 direction, double tNear, double tFar) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = float(origin.x), rh.ray.org_y = float(origin.y), rh.ray.org_z = float(origin.z);
    rh.ray.dir_x = float(direction.x), rh.ray.dir_y = float(direction.y), rh.ray.dir_z = float(direction.z);
    rh.ray.tnear = float(tNear), rh.ray.tfar = float(tFar);
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->top, &context, &rh);
    return impl_->hitOf(rh.ray, rh.hit, direction);
}

void RayScene::cast8(glm::dvec3 origin, std::span<const glm::dvec3> directions, double tNear, double tFar,
                     RangeHit* hits) const {
    require(directions.size() <= 8, "RayScene::cast8: at most 8 rays");
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT; // a beam's sub-rays: one origin, nearly one direction
    alignas(32) RTCRayHit8 rh{};
    alignas(32) int valid[8] = {};
    for (size_t i = 0; i < directions.size(); ++i) {
        valid[i] = -1;
        rh.ray.org_x[i] = float(origin.x), rh.ray.org_y[i] = float(origin.y), rh.ray.org_z[i] = float(origin.z);
        rh.ray.dir_x[i] = float(directions[i].x), rh.ray.dir_y[i] = float(directions[i].y);
        rh.ray.dir_z[i] = float(directions[i].z);
        rh.ray.tnear[i] = float(tNear), rh.ray.tfar[i] = float(tFar);
        rh.ray.mask[i] = 0xffffffffu;
        rh.hit.geomID[i] = rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect8(valid, impl_->top, &context, &rh);
    for (size_t i = 0; i < directions.size(); ++i) {
        RTCRayHitN* n = reinterpret_cast<RTCRayHitN*>(&rh);
        const RTCRayHit one = rtcGetRayHitFromRayHitN(n, 8, unsigned(i));
        hits[i] = impl_->hitOf(one.ray, one.hit, directions[i]);
    }
}

} // namespace sward

#include "range/range_sweep.h"

#include "common/error.h"
#include "common/hash.h"
#include "common/parallel_for.h"
#include "scene/world_tiles.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sward {

namespace {

constexpr double kDegrees = std::numbers::pi / 180.0;
constexpr uint64_t kRangeNoiseDomain = 0x52414e47454e3031ull; // "RANGEN01"
// Sub-ray hits closer than this along the beam form one echo (a pulse cannot separate them).
constexpr float kEchoSeparation = 0.5f;

// Diffuse reflectance at the sensors' near-infrared wavelength per semantic class (vegetation is bright there).
float reflectance(uint32_t label) {
    switch (label >> gpu::kInstanceBits) {
    case gpu::kSemanticGround:
    case gpu::kSemanticTurf:
    case gpu::kSemanticTrack:
        return 0.25f;
    case gpu::kSemanticObject:
        return 0.3f;
    case gpu::kSemanticFelled:
    case gpu::kSemanticCut:
        return 0.45f;
    default:
        return 0.5f; // standing plants
    }
}

// A beam's sub-rays: offsets (radians, in the beam's cross-section) and weights of a Gaussian beam whose 1/e^2 full
// angle is the divergence: the centre and rings of 6 (and 12) rays.
struct SubRay {
    glm::dvec2 offset;
    double weight;
};
std::vector<SubRay> subRays(const RangeSensorParams& s) {
    const double half = 0.5 * s.divergenceMrad * 1e-3;
    std::vector<SubRay> rays{{glm::dvec2(0.0), 1.0}};
    const uint32_t rings = s.subRays == 19 ? 2 : s.subRays == 7 ? 1 : 0;
    for (uint32_t ring = 1; ring <= rings; ++ring) {
        const double radius = half * double(ring) / double(rings + 1),
                     weight = std::exp(-2.0 * (radius / half) * (radius / half));
        for (uint32_t k = 0; k < 6 * ring; ++k) {
            const double phi = 2.0 * std::numbers::pi * double(k) / double(6 * ring);
            rays.push_back({radius * glm::dvec2(std::cos(phi), std::sin(phi)), weight});
        }
    }
    double total = 0.0;
    for (const SubRay& r : rays) total += r.weight;
    for (SubRay& r : rays) r.weight /= total;
    return rays;
}

struct SubHit {
    float distance, energy;
    uint32_t label, index, tile;
};

// The echoes of a beam from its sub-rays' hits (sorted by distance): the reported one's range, energy and label.
bool chooseReturn(std::vector<SubHit>& hits, RangeReturn mode, float& range, float& energy, uint32_t& label,
                  uint32_t& tile) {
    if (hits.empty()) return false;
    std::sort(hits.begin(), hits.end(), [](const SubHit& a, const SubHit& b) {
        return a.distance < b.distance || (a.distance == b.distance && a.index < b.index);
    });
    bool found = false;
    for (size_t begin = 0; begin < hits.size();) {
        size_t end = begin + 1;
        while (end < hits.size() && hits[end].distance - hits[end - 1].distance < kEchoSeparation) ++end;
        double e = 0.0, weighted = 0.0;
        const SubHit* strongest = &hits[begin];
        for (size_t i = begin; i < end; ++i) {
            e += hits[i].energy, weighted += double(hits[i].energy) * hits[i].distance;
            if (hits[i].energy > strongest->energy) strongest = &hits[i];
        }
        const float r = e > 0.0 ? float(weighted / e) : hits[begin].distance;
        const bool take = !found || mode == RangeReturn::Last || (mode == RangeReturn::Strongest && float(e) > energy);
        if (take) range = r, energy = float(e), label = strongest->label, tile = strongest->tile;
        found = true;
        if (mode == RangeReturn::First) break;
        begin = end;
    }
    return true;
}

} // namespace

PosedTriangles posedObject(const Scene& scene, size_t k, const ObjectModel& model, const Ground& ground, double time) {
    const std::vector<glm::dmat4> nodes = objectNodeTransforms(scene.objects[k], model, ground, time);
    PosedTriangles posed;
    posed.label = objectLabel(k);
    for (size_t n = 0; n < model.nodes.size(); ++n)
        for (const ModelPrimitive& prim : model.nodes[n].primitives) {
            const uint32_t base = uint32_t(posed.positions.size());
            for (const glm::vec3& p : prim.positions)
                posed.positions.push_back(glm::vec3(nodes[n] * glm::dvec4(p, 1.0)));
            for (uint32_t i : prim.indices) posed.indices.push_back(base + i);
        }
    return posed;
}

std::vector<PosedTriangles> posedObjects(const RangeWorld& world, double time) {
    std::vector<PosedTriangles> out;
    for (size_t k = 0; k < world.scene.objects.size() && k < world.models.size(); ++k)
        out.push_back(posedObject(world.scene, k, world.models[k], world.terrain, time));
    return out;
}

namespace {

// Columns per task: neighbouring beams meet the same plants, whose quads the first ray to reach them computes; one
// thread taking a run of neighbours keeps those plants (and their cache lines) off the other threads' way.
constexpr uint32_t kColumnsPerTask = 32;

struct SweepContext {
    const RayScene& rays;
    const RangeWorld& world;
    const RangeSensorParams& sensor;
    uint32_t sensorIndex, frame;
    double frameTime;
    const std::vector<SubRay>& pattern;
};

// Column c's beams: sub-rays cast, the echo chosen, noise and dropout; its points appended to `points` in ring order.
void sweepColumn(const SweepContext& x, RangeScan& scan, uint32_t c, std::vector<RangePoint>& points) {
    const RangeSensorParams& s = x.sensor;
    const double t = columnTime(s, c);
    const glm::dmat4 pose = s.type == RangeSensorType::TimeOfFlight
                                ? scan.startPose
                                : rangeSensorPose(x.world.scene, s, x.world.terrain, x.world.models, x.frameTime + t);
    const glm::dvec3 origin(pose[3]);
    const glm::dmat3 rotation(pose);
    std::vector<SubHit> hits;
    for (uint32_t ring = 0; ring < scan.channels; ++ring) {
        const glm::dvec3 beam = beamDirection(s, ring, c);
        const glm::dvec3 u =
            glm::normalize(std::abs(beam.z) < 0.9 ? glm::cross(beam, {0, 0, 1}) : glm::cross(beam, {1, 0, 0}));
        const glm::dvec3 v = glm::cross(beam, u);
        hits.clear();
        // Sub-rays in packets of up to 8, traversed together (one ray: cast alone).
        for (uint32_t first = 0; first < x.pattern.size(); first += 8) {
            const uint32_t count = std::min<uint32_t>(8, uint32_t(x.pattern.size()) - first);
            glm::dvec3 dirs[8];
            RangeHit found[8];
            for (uint32_t k = 0; k < count; ++k) {
                const SubRay& sub = x.pattern[first + k];
                dirs[k] = glm::normalize(rotation * glm::normalize(beam + sub.offset.x * u + sub.offset.y * v));
            }
            if (count == 1)
                found[0] = x.rays.cast(origin, dirs[0], s.minRange, s.maxRange);
            else
                x.rays.cast8(origin, std::span(dirs, count), s.minRange, s.maxRange, found);
            for (uint32_t k = 0; k < count; ++k) {
                if (!found[k].hit()) continue;
                const float cosine = float(std::abs(glm::dot(glm::dvec3(found[k].normal), dirs[k])));
                hits.push_back({found[k].distance,
                                float(x.pattern[first + k].weight) * reflectance(found[k].label) * cosine,
                                found[k].label, first + k, found[k].tile});
            }
        }
        RangePoint p;
        if (!chooseReturn(hits, s.returnMode, p.range, p.intensity, p.label, p.tile)) continue;
        const uint64_t key = hashKey({kRangeNoiseDomain, x.world.scene.seed, x.sensorIndex, x.frame, c, ring});
        if (s.dropout > 0.0 && unitDouble(mix64(key ^ 0x9e3779b97f4a7c15ull)) < s.dropout) continue;
        if (s.rangeNoise > 0.0) p.range = float(double(p.range) + s.rangeNoise * standardNormal(key));
        if (!(p.range > 0.0f)) continue;
        p.sensor = glm::vec3(beam * double(p.range));
        p.world = origin + rotation * (beam * double(p.range));
        p.time = float(t), p.ring = ring, p.column = c;
        scan.ranges[size_t(ring) * scan.columns + c] = p.range;
        points.push_back(p);
    }
}

} // namespace

namespace {

// A sweep's distinct firing times after `frameTime`, the first `count` of them: one for a ToF camera (a global
// shutter), else one per column.
std::vector<double> firingTimes(const RangeSensorParams& s, double frameTime, uint32_t count) {
    std::vector<double> times;
    const uint32_t n = std::min(count, s.type == RangeSensorType::TimeOfFlight ? 1u : s.columns());
    for (uint32_t c = 0; c < n; ++c) times.push_back(frameTime + columnTime(s, c));
    return times;
}

// The scene object a sensor is mounted on (mount.object).
size_t mountObject(const Scene& scene, const std::vector<ObjectModel>& models, const RangeSensorParams& s) {
    size_t k = 0;
    while (k < scene.objects.size() && scene.objects[k].name != s.mount.object) ++k;
    require(k < scene.objects.size() && k < models.size(), scene.source + ": range sensor '" + s.name +
                                                               "': 'mount.object' names no scene object: '" +
                                                               s.mount.object + "'");
    return k;
}

// The xy a sweep's ground must cover (fixed, path: the sensor's origins; object: the object's path positions) and the
// margin around them (object: its footprint, as objectGround's, bounded by the model's farthest corner).
void sweepArea(const Scene& scene, const std::vector<ObjectModel>& models, const RangeSensorParams& s, double frameTime,
               glm::dvec2& lo, glm::dvec2& hi, double& margin) {
    const RangeMount& m = s.mount;
    std::vector<glm::dvec2> xy;
    margin = 1.0;
    if (m.kind == RangeMount::Kind::Fixed) {
        xy.push_back(glm::dvec2(m.position));
    } else if (m.kind == RangeMount::Kind::Path) {
        for (double t : firingTimes(s, frameTime, ~0u)) xy.push_back(pathPoseXY(m.path, t));
    } else {
        const size_t k = mountObject(scene, models, s);
        const ObjectModel& model = models[k];
        const glm::dvec2 corner =
            glm::max(glm::abs(glm::dvec2(model.boundsMin)), glm::abs(glm::dvec2(model.boundsMax)));
        margin += std::sqrt(2.0) * glm::length(corner) * scene.objects[k].scale;
        for (double t : firingTimes(s, frameTime, ~0u)) xy.push_back(pathPoseXY(scene.objects[k].path, t));
    }
    lo = hi = xy[0];
    for (const glm::dvec2& p : xy) lo = glm::min(lo, p), hi = glm::max(hi, p);
}

} // namespace

Ground sweepGround(const Scene& scene, const std::vector<ObjectModel>& models, const RangeSensorParams& sensor,
                   double frameTime) {
    glm::dvec2 lo, hi;
    double margin = 0.0;
    sweepArea(scene, models, sensor, frameTime, lo, hi, margin);
    return latticeGround(scene, lo, hi, margin);
}

std::vector<glm::dvec2> sweepOrigins(const Scene& scene, const std::vector<ObjectModel>& models,
                                     const RangeSensorParams& s, const Ground& ground, double frameTime,
                                     uint32_t count) {
    if (s.mount.kind == RangeMount::Kind::Fixed) return {glm::dvec2(s.mount.position)};
    std::vector<glm::dvec2> origins;
    for (double t : firingTimes(s, frameTime, count))
        origins.push_back(s.mount.kind == RangeMount::Kind::Path
                              ? pathPoseXY(s.mount.path, t)
                              : glm::dvec2(rangeSensorPose(scene, s, ground, models, t)[3]));
    return origins;
}

std::vector<glm::dvec2> rangeSensorStarts(const Scene& scene, const std::vector<ObjectModel>& models,
                                          double frameTime) {
    std::vector<glm::dvec2> starts;
    for (const RangeSensorParams& s : scene.rangeSensors) {
        const Ground ground =
            s.mount.kind == RangeMount::Kind::Object ? sweepGround(scene, models, s, frameTime) : Ground();
        starts.push_back(sweepOrigins(scene, models, s, ground, frameTime, 1)[0]);
    }
    return starts;
}

RangeScan sweepSensor(const RayScene& rays, const RangeWorld& world, uint32_t sensorIndex, uint32_t frame,
                      double frameTime, uint32_t threads) {
    const RangeSensorParams& s = world.scene.rangeSensors.at(sensorIndex);
    RangeScan scan;
    scan.channels = s.channels(), scan.columns = s.columns();
    scan.tiles = world.scene.world.enabled && uint64_t(world.scene.world.tilesX) * world.scene.world.tilesY > 1;
    scan.ranges.assign(size_t(scan.channels) * scan.columns, 0.0f);
    scan.startPose = rangeSensorPose(world.scene, s, world.terrain, world.models, frameTime + columnTime(s, 0));
    scan.endPose =
        rangeSensorPose(world.scene, s, world.terrain, world.models, frameTime + columnTime(s, scan.columns - 1));
    const std::vector<SubRay> pattern = subRays(s);
    const SweepContext context{rays, world, s, sensorIndex, frame, frameTime, pattern};
    // Each task fills its own slot; the slots are joined in column order, so the points are the same on any threads.
    const uint32_t tasks = (scan.columns + kColumnsPerTask - 1) / kColumnsPerTask;
    std::vector<std::vector<RangePoint>> perTask(tasks);
    parallelFor(tasks, threads, [&](uint32_t task, uint32_t) {
        const uint32_t end = std::min(scan.columns, (task + 1) * kColumnsPerTask);
        for (uint32_t c = task * kColumnsPerTask; c < end; ++c) sweepColumn(context, scan, c, perTask[task]);
    });
    for (std::vector<RangePoint>& points : perTask) scan.points.insert(scan.points.end(), points.begin(), points.end());
    return scan;
}

} // namespace sward

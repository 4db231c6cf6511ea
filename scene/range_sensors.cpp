#include "scene/range_sensors.h"

#include "common/error.h"
#include "common/json_reader.h"
#include "common/optional_components.h"
#include "scene/scene.h"

#include <cmath>
#include <numbers>
#include <set>

namespace sward {

namespace {

std::vector<double> evenlySpaced(double lo, double hi, uint32_t count) {
    std::vector<double> out(count);
    for (uint32_t i = 0; i < count; ++i) out[i] = count == 1 ? lo : lo + (hi - lo) * double(i) / double(count - 1);
    return out;
}

// Public data-sheet figures (nominal; a user's unit may differ): channel layout, resolution, rate, range, divergence
// and range precision (one standard deviation).
RangeSensorParams preset(const std::string& name, const std::string& where) {
    RangeSensorParams p;
    p.preset = name;
    if (name == "VLP-16") { // Velodyne VLP-16 (Puck): 16 x 2 degrees, 0.2 degrees at 10 Hz, 100 m, +-3 cm
        p.elevationsDegrees = evenlySpaced(-15.0, 15.0, 16);
        p.azimuthStepDegrees = 0.2, p.maxRange = 100.0, p.minRange = 0.5;
        p.divergenceMrad = 3.0, p.rangeNoise = 0.015;
    } else if (name == "HDL-32E") { // Velodyne HDL-32E: -30.67 .. +10.67 degrees, 0.16 degrees at 10 Hz, 100 m
        p.elevationsDegrees = evenlySpaced(-30.67, 10.67, 32);
        p.azimuthStepDegrees = 0.16, p.maxRange = 100.0, p.minRange = 1.0;
        p.divergenceMrad = 2.0, p.rangeNoise = 0.01;
    } else if (name == "OS1-64") { // Ouster OS1-64: 64 channels over 45 degrees, 1024 columns at 10 Hz, 120 m
        p.elevationsDegrees = evenlySpaced(-22.5, 22.5, 64);
        p.azimuthStepDegrees = 360.0 / 1024.0, p.maxRange = 120.0, p.minRange = 0.3;
        p.divergenceMrad = 2.3, p.rangeNoise = 0.015;
    } else if (name == "LMS111") { // SICK LMS111: 270 degrees in 0.5 degree steps at 25 Hz, 20 m, 12 mm
        p.type = RangeSensorType::Scanner;
        p.elevationsDegrees = {0.0};
        p.angleMinDegrees = -135.0, p.angleMaxDegrees = 135.0, p.azimuthStepDegrees = 0.5, p.rateHz = 25.0;
        p.maxRange = 20.0, p.minRange = 0.5, p.divergenceMrad = 8.7, p.rangeNoise = 0.012;
    } else if (name == "UST-10LX") { // Hokuyo UST-10LX: 270 degrees in 0.25 degree steps at 40 Hz, 10 m, 40 mm
        p.type = RangeSensorType::Scanner;
        p.elevationsDegrees = {0.0};
        p.angleMinDegrees = -135.0, p.angleMaxDegrees = 135.0, p.azimuthStepDegrees = 0.25, p.rateHz = 40.0;
        p.maxRange = 10.0, p.minRange = 0.06, p.rangeNoise = 0.04;
    } else if (name == "AzureKinect-NFOV") { // Azure Kinect depth, NFOV unbinned: 640 x 576, 65 degrees, 0.5-3.86 m
        p.type = RangeSensorType::TimeOfFlight;
        p.width = 640, p.height = 576, p.fovYDegrees = 65.0, p.rateHz = 30.0;
        p.minRange = 0.5, p.maxRange = 3.86, p.rangeNoise = 0.0017;
    } else {
        std::string names;
        for (const std::string& n : rangeSensorPresets()) names += (names.empty() ? "" : ", ") + n;
        throw Error(where + " names no preset: '" + name + "' (presets: " + names + ")");
    }
    return p;
}

void readMount(JsonReader r, RangeMount& m) {
    const bool object = r.has("object"), path = r.has("path");
    if (object && path) r.fail("'" + r.path() + "' takes either 'object' or 'path', not both");
    m.pitchDegrees = r.number("pitch_deg", m.pitchDegrees, -90.0, 90.0);
    if (object) {
        m.kind = RangeMount::Kind::Object;
        m.object = r.string("object", "");
        m.node = r.string("node", "");
        if (m.object.empty() || m.node.empty())
            r.fail("'" + r.path() + "' needs 'object' and 'node' (names of a scene object and a node of its model)");
        m.offset = r.vector<3>("offset", m.offset, -1e3, 1e3);
    } else {
        if (path) {
            m.kind = RangeMount::Kind::Path;
            m.path = parsePath(*r.raw("path"), r.source(), r.childPath("path"));
        } else {
            if (!r.has("position")) r.fail("'" + r.path() + "' needs 'position', 'path' or 'object'");
            m.position = r.vector<3>("position", m.position, -1e7, 1e7);
            m.useHeightAboveGround = r.boolean("on_ground", true);
            m.heightAboveGround = r.number("height_above_ground", m.heightAboveGround, -1e4, 1e4);
            m.yawDegrees = r.number("yaw_deg", m.yawDegrees, -360.0, 360.0);
        }
    }
    r.finish();
}

std::vector<double> readElevations(JsonReader& r) {
    const nlohmann::json* array = r.raw("elevations_deg");
    const std::string where = r.source() + ": '" + r.childPath("elevations_deg") + "'";
    if (!array->is_array() || array->empty() || array->size() > 256)
        throw Error(where + " must be an array of 1..256 angles in degrees");
    std::vector<double> out;
    for (const nlohmann::json& v : *array) {
        if (!v.is_number() || !std::isfinite(v.get<double>()) || std::abs(v.get<double>()) > 90.0)
            throw Error(where + " must hold numbers in [-90, 90]");
        out.push_back(v.get<double>());
    }
    return out;
}

RangeSensorParams readSensor(JsonReader r, size_t index) {
    const std::string where = r.source() + ": '" + r.path() + "'";
    RangeSensorParams p;
    if (r.has("preset")) p = preset(r.string("preset", ""), where);
    p.name = r.string("name", "sensor" + std::to_string(index));
    const int type = r.choice("type", int(p.type), {"lidar", "scanner", "tof"});
    if (!p.preset.empty() && type != int(p.type))
        r.fail("'" + r.childPath("type") + "' contradicts preset '" + p.preset + "'");
    p.type = RangeSensorType(type);
    if (p.type == RangeSensorType::Lidar && p.elevationsDegrees.empty())
        p.elevationsDegrees = evenlySpaced(-15, 15, 16);
    if (p.type == RangeSensorType::Scanner) p.elevationsDegrees = {0.0};
    if (r.has("elevations_deg")) {
        if (p.type != RangeSensorType::Lidar) r.fail("'" + r.childPath("elevations_deg") + "' applies to a lidar only");
        p.elevationsDegrees = readElevations(r);
    }
    p.azimuthStepDegrees = r.number("angle_step_deg", p.azimuthStepDegrees, 0.01, 90.0);
    if (p.type == RangeSensorType::Scanner || r.has("angle_range_deg")) {
        glm::dvec2 range = r.vector<2>("angle_range_deg", {p.angleMinDegrees, p.angleMaxDegrees}, -180.0, 180.0);
        if (!(range.x < range.y)) r.fail("'" + r.childPath("angle_range_deg") + "' must be [min, max] with min < max");
        p.angleMinDegrees = range.x, p.angleMaxDegrees = range.y;
    }
    p.rateHz = r.number("rate_hz", p.rateHz, 0.1, 1000.0);
    glm::uvec2 size = r.wholeVector<2>("resolution", {p.width, p.height}, 1, 4096);
    p.width = size.x, p.height = size.y;
    p.fovYDegrees = r.number("fov_y_deg", p.fovYDegrees, 1.0, 170.0);
    glm::dvec2 range = r.vector<2>("range", {p.minRange, p.maxRange}, 0.0, 1e4);
    if (!(range.x < range.y)) r.fail("'" + r.childPath("range") + "' must be [min, max] metres with min < max");
    p.minRange = range.x, p.maxRange = range.y;
    p.divergenceMrad = r.number("divergence_mrad", p.divergenceMrad, 0.0, 100.0);
    p.subRays = uint32_t(r.integer("sub_rays", p.subRays, 1, 19));
    if (p.subRays != 1 && p.subRays != 7 && p.subRays != 19)
        r.fail("'" + r.childPath("sub_rays") + "' must be 1, 7 or 19");
    if (p.subRays > 1 && p.divergenceMrad == 0.0)
        r.fail("'" + r.childPath("sub_rays") + "' > 1 needs a beam divergence ('divergence_mrad' > 0)");
    p.returnMode = RangeReturn(r.choice("return", int(p.returnMode), {"first", "strongest", "last"}));
    p.rangeNoise = r.number("range_noise_m", p.rangeNoise, 0.0, 10.0);
    p.dropout = r.number("dropout", p.dropout, 0.0, 1.0);
    readMount(r.child("mount"), p.mount);
    if (uint64_t(p.columns()) * p.channels() > (uint64_t(1) << 24))
        r.fail("'" + r.path() + "' fires more than 2^24 beams per sweep");
    r.finish();
    return p;
}

constexpr double kDegrees = std::numbers::pi / 180.0;

glm::dmat4 frameFromAxes(glm::dvec3 forward, glm::dvec3 up, glm::dvec3 origin, double pitchDegrees) {
    forward = glm::normalize(forward), up = glm::normalize(up - forward * glm::dot(forward, up));
    const double p = pitchDegrees * kDegrees;
    const glm::dvec3 x = forward * std::cos(p) - up * std::sin(p), z = up * std::cos(p) + forward * std::sin(p);
    return glm::dmat4(glm::dvec4(x, 0.0), glm::dvec4(glm::cross(z, x), 0.0), glm::dvec4(z, 0.0),
                      glm::dvec4(origin, 1.0));
}

} // namespace

uint32_t RangeSensorParams::columns() const {
    if (type == RangeSensorType::TimeOfFlight) return width;
    const double span = type == RangeSensorType::Lidar && angleMinDegrees == -180.0 && angleMaxDegrees == 180.0
                            ? 360.0
                            : angleMaxDegrees - angleMinDegrees;
    const bool closed = span == 360.0; // a full turn does not fire its first azimuth twice
    return uint32_t(std::floor(span / azimuthStepDegrees + 1e-9)) + (closed ? 0u : 1u);
}

glm::dmat4 rangeSensorPose(const Scene& scene, const RangeSensorParams& sensor, const Ground& terrain,
                           const std::vector<ObjectModel>& models, double time) {
    const RangeMount& m = sensor.mount;
    switch (m.kind) {
    case RangeMount::Kind::Fixed: {
        glm::dvec3 p = m.position;
        if (m.useHeightAboveGround) p.z = terrain.height(glm::vec2(p)) + m.heightAboveGround;
        const double yaw = m.yawDegrees * kDegrees;
        return frameFromAxes({std::cos(yaw), std::sin(yaw), 0.0}, {0, 0, 1}, p, m.pitchDegrees);
    }
    case RangeMount::Kind::Path: {
        const PathPose pose = pathPose(m.path, terrain, time);
        return frameFromAxes(glm::dvec3(pose.heading, 0.0), {0, 0, 1}, pose.position, m.pitchDegrees);
    }
    case RangeMount::Kind::Object:
        break;
    }
    size_t k = 0;
    while (k < scene.objects.size() && scene.objects[k].name != m.object) ++k;
    require(k < scene.objects.size() && k < models.size(), scene.source + ": range sensor '" + sensor.name +
                                                               "': 'mount.object' names no scene object: '" + m.object +
                                                               "'");
    const glm::dmat4 node = objectNodeToWorld(scene.objects[k], models[k], m.node, terrain, time);
    // Node frame: -y forward, +x left, +z up (objects.h).
    return frameFromAxes(glm::dvec3(node * glm::dvec4(0, -1, 0, 0)), glm::dvec3(node * glm::dvec4(0, 0, 1, 0)),
                         glm::dvec3(node * glm::dvec4(m.offset, 1.0)), m.pitchDegrees);
}

glm::dvec3 beamDirection(const RangeSensorParams& s, uint32_t ring, uint32_t column) {
    if (s.type == RangeSensorType::TimeOfFlight) {
        const double f = 0.5 * double(s.height) / std::tan(0.5 * s.fovYDegrees * kDegrees);
        return glm::normalize(
            glm::dvec3(f, -(double(column) + 0.5 - 0.5 * s.width), -(double(ring) + 0.5 - 0.5 * s.height)));
    }
    const double az = (s.angleMinDegrees + double(column) * s.azimuthStepDegrees) * kDegrees;
    const double el = s.elevationsDegrees[ring] * kDegrees;
    return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

double columnTime(const RangeSensorParams& s, uint32_t column) {
    if (s.type == RangeSensorType::TimeOfFlight) return 0.0;
    return double(column) * s.azimuthStepDegrees / 360.0 / s.rateHz;
}

std::vector<std::string> rangeSensorPresets() {
    return {"VLP-16", "HDL-32E", "OS1-64", "LMS111", "UST-10LX", "AzureKinect-NFOV"};
}

std::vector<RangeSensorParams> parseRangeSensors(JsonReader& scene) {
    std::vector<RangeSensorParams> sensors;
    std::set<std::string> names;
    for (JsonReader& r : scene.objects("range_sensors")) {
        // Refused before anything is read, rendered or written in a build without Embree.
        if (sensors.empty()) requireComponent(Component::Embree, scene.source() + ": 'range_sensors'");
        RangeSensorParams p = readSensor(std::move(r), sensors.size());
        if (!names.insert(p.name).second)
            throw Error(scene.source() + ": 'range_sensors' names '" + p.name + "' twice (names must be unique)");
        for (char c : p.name)
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_')
                throw Error(scene.source() + ": range sensor name '" + p.name +
                            "' may hold only letters, digits, '-' and '_' (it names a folder)");
        sensors.push_back(std::move(p));
    }
    // Priced before anything is cast: 2^24 beams of 19 sub-rays each, in several sensors, cost minutes a frame.
    uint64_t rays = 0;
    for (const RangeSensorParams& p : sensors) rays += uint64_t(p.columns()) * p.channels() * p.subRays;
    if (rays > kMaxRangeRaysPerFrame)
        throw Error(scene.source() + ": 'range_sensors' cast " + std::to_string(rays) +
                    " rays a frame (beams x 'sub_rays', all sensors), over the limit of " +
                    std::to_string(kMaxRangeRaysPerFrame) +
                    "; lower 'resolution', the channels, 'sub_rays' or "
                    "raise 'angle_step_deg'");
    return sensors;
}

} // namespace sward

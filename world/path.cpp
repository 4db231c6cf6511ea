#include "world/path.h"

#include "common/error.h"
#include "common/json_reader.h"
#include "world/ground.h"

#include <cmath>

namespace sward {

double pathLength(const PathParams& path) {
    double length = 0.0;
    for (size_t i = 1; i < path.points.size(); ++i) length += glm::distance(path.points[i - 1], path.points[i]);
    return length;
}

namespace {

// Point and heading at arc length s.
std::pair<glm::dvec2, glm::dvec2> pointAt(const PathParams& path, double s) {
    require(!path.points.empty(), "a path needs at least one point");
    if (path.points.size() == 1) return {path.points[0], glm::dvec2(1.0, 0.0)};
    double total = pathLength(path);
    if (total <= 0.0) return {path.points[0], glm::dvec2(1.0, 0.0)};
    s = path.loop ? std::fmod(std::fmod(s, total) + total, total) : std::clamp(s, 0.0, total);
    for (size_t i = 1; i < path.points.size(); ++i) {
        glm::dvec2 a = path.points[i - 1], b = path.points[i];
        double segment = glm::distance(a, b);
        if (segment <= 0.0) continue;
        if (s <= segment || i + 1 == path.points.size()) {
            double t = std::min(s / segment, 1.0);
            return {a + (b - a) * t, (b - a) / segment};
        }
        s -= segment;
    }
    return {path.points.back(), glm::dvec2(1.0, 0.0)};
}

} // namespace

PathPose pathPose(const PathParams& path, const Ground& terrain, double time) {
    double s = std::max(time - path.startTime, 0.0) * path.speed;
    auto [xy, heading] = pointAt(path, s);
    double z = double(terrain.height(glm::vec2(xy))) + path.heightAboveGround;
    return {glm::dvec3(xy, z), heading, s};
}

glm::dvec2 pathPoseXY(const PathParams& path, double time) {
    return pointAt(path, std::max(time - path.startTime, 0.0) * path.speed).first;
}

glm::dvec2 pathPointAheadXY(const PathParams& path, double time, double ahead) {
    double s = std::max(time - path.startTime, 0.0) * path.speed + ahead;
    auto [xy, heading] = pointAt(path, s);
    if (!path.loop && s > pathLength(path)) xy += heading * (s - pathLength(path)); // look beyond the end
    return xy;
}

glm::dvec3 pathPointAhead(const PathParams& path, const Ground& terrain, double time, double ahead) {
    const glm::dvec2 xy = pathPointAheadXY(path, time, ahead);
    return glm::dvec3(xy, double(terrain.height(glm::vec2(xy))));
}

PathParams parsePath(const nlohmann::json& json, const std::string& source, const std::string& jsonPath) {
    JsonReader r(json, source, jsonPath);
    PathParams path;
    r.required("points", "[[x, y], ...]");
    path.points = r.vectors<2>("points", -1e9, 1e9);
    if (path.points.empty()) r.fail(r.name("points") + " must not be empty");
    path.speed = r.number("speed", path.speed, 0.0, 1000.0);
    path.heightAboveGround = r.number("height_above_ground", path.heightAboveGround, -100.0, 10000.0);
    path.startTime = r.number("start_time", path.startTime, 0.0, 1e9);
    path.loop = r.boolean("loop", path.loop);
    r.finish();
    return path;
}

} // namespace sward

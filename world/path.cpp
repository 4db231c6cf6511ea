#include "world/path.h"

#include "common/error.h"
#include "world/heightfield.h"

#include <nlohmann/json.hpp>

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

PathPose pathPose(const PathParams& path, const Heightfield& terrain, double time) {
    double s = std::max(time - path.startTime, 0.0) * path.speed;
    auto [xy, heading] = pointAt(path, s);
    double z = double(terrain.height(glm::vec2(xy))) + path.heightAboveGround;
    return {glm::dvec3(xy, z), heading, s};
}

glm::dvec3 pathPointAhead(const PathParams& path, const Heightfield& terrain, double time, double ahead) {
    double s = std::max(time - path.startTime, 0.0) * path.speed + ahead;
    auto [xy, heading] = pointAt(path, s);
    if (!path.loop && s > pathLength(path)) xy += heading * (s - pathLength(path)); // look beyond the end
    return glm::dvec3(xy, double(terrain.height(glm::vec2(xy))));
}

PathParams parsePath(const nlohmann::json& json, const std::string& where) {
    auto fail = [&](const std::string& what) { throw Error(where + ": " + what); };
    if (!json.is_object()) fail("must be an object with \"points\"");
    PathParams path;
    for (auto it = json.begin(); it != json.end(); ++it) {
        const std::string& key = it.key();
        const nlohmann::json& v = it.value();
        if (key == "points") {
            if (!v.is_array() || v.empty()) fail("'points' must be a non-empty array of [x, y]");
            for (const nlohmann::json& p : v) {
                if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number() ||
                    !std::isfinite(p[0].get<double>()) || !std::isfinite(p[1].get<double>()))
                    fail("'points' must hold [x, y] pairs of finite numbers");
                path.points.emplace_back(p[0].get<double>(), p[1].get<double>());
            }
        } else if (key == "speed" || key == "height_above_ground" || key == "start_time") {
            if (!v.is_number() || !std::isfinite(v.get<double>())) fail("'" + key + "' must be a finite number");
            double x = v.get<double>();
            if (key == "speed") {
                if (x < 0.0 || x > 1000.0) fail("'speed' must be between 0 and 1000 m/s");
                path.speed = x;
            } else if (key == "height_above_ground") {
                if (x < -100.0 || x > 10000.0) fail("'height_above_ground' must be between -100 and 10000 m");
                path.heightAboveGround = x;
            } else {
                if (x < 0.0) fail("'start_time' must not be negative");
                path.startTime = x;
            }
        } else if (key == "loop") {
            if (!v.is_boolean()) fail("'loop' must be true or false");
            path.loop = v.get<bool>();
        } else {
            fail("unknown key '" + key + "'");
        }
    }
    if (path.points.empty()) fail("'points' is required");
    return path;
}

} // namespace sward

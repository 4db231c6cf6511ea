// Paths for moving cameras, vehicles and colliders: a polyline in the ground plane travelled at constant
// speed, with heights taken from the terrain. Motion is a pure function of simulation time, so any frame of a
// sequence can be rendered on its own (shards, resume) and lands exactly where a full run puts it.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace sward {

class Ground;

struct PathParams {
    std::vector<glm::dvec2> points;  // world xy waypoints, metres; at least 2 for motion
    double speed = 1.0;              // metres per second along the polyline
    double heightAboveGround = 0.0;  // metres above the terrain
    double startTime = 0.0;          // seconds before which the object waits at the first point
    bool loop = false;               // wrap around instead of stopping at the last point
};

struct PathPose {
    glm::dvec3 position;  // world, z on the terrain + heightAboveGround
    glm::dvec2 heading;   // unit xy direction of travel
    double distance = 0;  // metres travelled
};

// Pose at simulation time `time`. Requires at least one point.
PathPose pathPose(const PathParams& path, const Ground& terrain, double time);
// Point `ahead` metres further along the path from the pose at `time` (clamped to the end unless looping).
glm::dvec3 pathPointAhead(const PathParams& path, const Ground& terrain, double time, double ahead);
// The xy of pathPose and pathPointAhead, which need no ground (e.g. to know where to make the ground resident).
glm::dvec2 pathPoseXY(const PathParams& path, double time);
glm::dvec2 pathPointAheadXY(const PathParams& path, double time, double ahead);
// Total polyline length in metres.
double pathLength(const PathParams& path);

// Reads {"points": [[x, y], ...], "speed", "height_above_ground", "start_time", "loop"} ("points" required and
// non-empty); errors name `source` and the JSON path, e.g. "scene.json: 'camera.path.speed' must be ...".
PathParams parsePath(const nlohmann::json& json, const std::string& source, const std::string& jsonPath);

} // namespace sward

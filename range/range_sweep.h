// One sweep of a range sensor: its beams (directions in the sensor frame, firing times), its pose as it moves during
// the sweep, sub-rays over the beam's divergence, echoes and the return it reports, range noise and dropout.
//
// Beams fire column by column (a LiDAR's azimuth steps, a scanner's angles; every ring of a column at once), column c
// at time frameTime + c / (columns * rate); a ToF camera's pixels all at frameTime (a global shutter). The sensor moves
// between columns (its mount's pose at each column's time); the world is the one of the frame's tick (RayScene).
// Every random quantity is a counter-based hash of (seed, sensor, frame, column, ring): bitwise reproducible on any
// number of threads.
#pragma once

#include "range/ray_scene.h"
#include "scene/scene.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace sward {

// One beam's return.
struct RangePoint {
    glm::vec3 sensor{0.0f}; // in the sensor frame at its firing time (x forward, y left, z up), metres
    glm::dvec3 world{0.0};  // world frame
    float range = 0.0f;     // metres along the beam, noise included
    float intensity = 0.0f; // the echo's share of the beam's energy times the surfaces' reflectance (0..1)
    float time = 0.0f;      // seconds after the sweep's start
    uint32_t ring = 0, column = 0;
    uint32_t label = 0; // (semantic class << 24) | instance of the surface that returned most of the echo
    uint32_t tile = 0;  // a world's plant: that surface's tile, y * tiles_x + x + 1 (RangeHit::tile); else 0
};

struct RangeScan {
    uint32_t channels = 0, columns = 0;
    std::vector<RangePoint> points;          // beams with a return, in firing order (column, then ring)
    std::vector<float> ranges;               // per beam, ring-major (ring * columns + column): range, 0 = no return
    glm::dmat4 startPose{1.0}, endPose{1.0}; // world-from-sensor at the first and the last column's time
    bool tiles = false;                      // a world of several tiles: each point names its plant's tile
};

// What a sweep needs of the scene besides the RayScene.
struct RangeWorld {
    const Scene& scene;
    const Ground& terrain;
    const std::vector<ObjectModel>& models;
};

// The scene objects' triangles at simulation time `time`, world space, labelled as the truth pass labels them.
std::vector<PosedTriangles> posedObjects(const RangeWorld& world, double time);
// Object k's (of scene.objects, with its `model`) standing on `ground` (a world: its objectGround).
PosedTriangles posedObject(const Scene& scene, size_t k, const ObjectModel& model, const Ground& ground, double time);

// The ground a range sensor of a world stands on during its sweep from `frameTime`: the world's lattice ground
// (latticeGround: the tiles' heights bitwise) around the sensor's origins (fixed, path mounts), or under its object's
// footprint along the object's path (object mounts; `models` as loadObjectModels returns them), as a camera stands on
// cameraGround or its object's objectGround. Throws sward::Error naming the sensor for a mount on no scene object.
Ground sweepGround(const Scene& scene, const std::vector<ObjectModel>& models, const RangeSensorParams& sensor,
                   double frameTime);
// The xy of a sensor's origin at the first `count` distinct firing times of its sweep from `frameTime` (one for a fixed
// mount or a ToF camera, else one per column), standing on `ground` (sweepGround; unused for fixed and path mounts):
// where a world needs its tiles.
std::vector<glm::dvec2> sweepOrigins(const Scene& scene, const std::vector<ObjectModel>& models,
                                     const RangeSensorParams& sensor, const Ground& ground, double frameTime,
                                     uint32_t count = ~0u);
// Where each range sensor's sweep of the frame at `frameTime` starts (xy): interest points of a world (the tiles its
// rays meet are made resident around them, as around the cameras).
std::vector<glm::dvec2> rangeSensorStarts(const Scene& scene, const std::vector<ObjectModel>& models, double frameTime);

// Sensor `sensorIndex` (of scene.rangeSensors) sweeping from `frameTime` (frame `frame`) through `rays`, which must hold
// the world of that frame's tick. Threads as parallelFor.
RangeScan sweepSensor(const RayScene& rays, const RangeWorld& world, uint32_t sensorIndex, uint32_t frame,
                      double frameTime, uint32_t threads = 0);

} // namespace sward

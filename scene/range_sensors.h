// Range sensors of a scene (`range_sensors`, docs/scene-format.md): rotating multi-beam LiDARs, 2D laser scanners
// and time-of-flight depth cameras, mounted like the camera rig (fixed, on a path, or on a scene object's node).
// What each sensor fires is a list of beams (range/range_beams.h); the ray casting is range/ (Embree).
//
// Sensor frame: x forward, y left, z up (the ROS / KITTI Velodyne convention). A LiDAR's azimuth is measured from
// +x towards +y, its channels' elevations from the xy plane, up positive; a ToF camera looks along +x.
#pragma once

#include "world/path.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace sward {

class Ground;
class JsonReader;
struct ObjectModel;
struct Scene;

enum class RangeSensorType { Lidar, Scanner, TimeOfFlight };
// Which echo of a beam becomes its point when sub-rays (beam divergence) meet several surfaces.
enum class RangeReturn { First, Strongest, Last };

struct RangeMount {
    enum class Kind { Fixed, Path, Object } kind = Kind::Fixed;
    glm::dvec3 position{0.0};       // Fixed: world position; z replaced (on_ground) by the terrain + heightAboveGround
    double heightAboveGround = 1.0; // Fixed: metres above the terrain (a path has its own height_above_ground)
    bool useHeightAboveGround = true;
    double yawDegrees = 0.0;   // Fixed: heading of the sensor's +x, counter-clockwise from world +x
    double pitchDegrees = 0.0; // all: downward tilt of +x (positive looks down)
    PathParams path;           // Path: heading = direction of travel
    std::string object, node;  // Object: the node's frame (-y forward, +x left, +z up) carries the sensor
    glm::dvec3 offset{0.0};    // Object: sensor origin in the node's frame, metres
};

struct RangeSensorParams {
    std::string name; // unique; names the output folder
    RangeSensorType type = RangeSensorType::Lidar;
    std::string preset; // the data-sheet preset it started from ("" = none)
    RangeMount mount;
    // LiDAR: channel elevations (degrees, ring 0 first), azimuth step (degrees) and rotation rate; the sweep of frame
    // f starts at the frame's time and lasts 1 / rateHz. Scanner: one channel, angles [angleMin, angleMax] in steps.
    std::vector<double> elevationsDegrees;
    double azimuthStepDegrees = 0.2;
    double angleMinDegrees = -180.0, angleMaxDegrees = 180.0; // scanner (and a LiDAR's horizontal window)
    double rateHz = 10.0;                                     // rotations (LiDAR, scanner) or frames (ToF) per second
    // ToF camera: image size and vertical field of view (square pixels, principal point at the centre).
    uint32_t width = 320, height = 240;
    double fovYDegrees = 45.0;
    double minRange = 0.3, maxRange = 100.0; // metres; no return outside
    double divergenceMrad = 0.0;             // full-angle beam divergence; > 0: sub-rays over the beam's cone
    uint32_t subRays = 1;                    // rays per beam (1, or 7 / 19: a centre and rings of a hexagonal pattern)
    RangeReturn returnMode = RangeReturn::Strongest;
    double rangeNoise = 0.0; // standard deviation of the range, metres (counter-based, reproducible)
    double dropout = 0.0;    // probability that a beam with an echo returns nothing

    uint32_t channels() const {
        return type == RangeSensorType::TimeOfFlight ? height : uint32_t(elevationsDegrees.size());
    }
    uint32_t columns() const; // azimuth steps (LiDAR, scanner) or image width (ToF)
};

// How far (xy, metres) a plant may reach out of the box of its roots' field, or of its tile: the margin of the fields
// and world tiles a range sensor's rays can meet (range/plant_fields.cpp, range/range_recorder.cpp, checkWorldDrawable).
inline constexpr double kPlantLean = 2.0;

// The presets' names, for messages and docs: "VLP-16", "HDL-32E", "OS1-64" (LiDAR), "LMS111", "UST-10LX" (scanner),
// "ToF-VGA" (time of flight).
std::vector<std::string> rangeSensorPresets();

// World-from-sensor transform of `sensor` at simulation time `time` (its mount: fixed, on a path or on an object's
// node; `models` as loadObjectModels returns them, needed only for an object mount).
glm::dmat4 rangeSensorPose(const Scene& scene, const RangeSensorParams& sensor, const Ground& terrain,
                           const std::vector<ObjectModel>& models, double time);

// Unit direction (sensor frame) of beam (ring, column); a ToF camera's pixel (column, ring) through its centre.
glm::dvec3 beamDirection(const RangeSensorParams& sensor, uint32_t ring, uint32_t column);
// Seconds after the sweep's start at which column `column` fires: a LiDAR or scanner turns at rateHz, so column c
// fires at c * step / 360 / rate; a ToF camera's pixels all at 0 (global shutter).
double columnTime(const RangeSensorParams& sensor, uint32_t column);

// Rays all range sensors cast for one frame (beams x sub-rays), at most 2^25 (33.5 million: ten VGA ToF cameras with
// 7 sub-rays each, or 512 OS1-64 LiDARs); one sensor's 2^24 beams of 19 sub-rays each cost minutes a frame.
inline constexpr uint64_t kMaxRangeRaysPerFrame = uint64_t(1) << 25;
// Parses the scene's `range_sensors` array (each element an object, keys in docs/scene-format.md); a preset sets the
// defaults its other keys then override. Errors name the sensor's JSON path; more than kMaxRangeRaysPerFrame rays
// in all is refused naming the estimate.
std::vector<RangeSensorParams> parseRangeSensors(JsonReader& scene);

} // namespace sward

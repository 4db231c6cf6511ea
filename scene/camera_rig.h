// Camera rigs: the scene's stereo pair (or single camera) at a simulation time.
//
// A rig is rectified: both cameras share orientation and intrinsics, the right optical centre is the left one
// moved `baseline` metres along the cameras' +x axis, so a point at planar depth Z appears d = f * B / Z pixels
// further left in the right image (x_right = x_left - d). The rig centre is halfway between the two cameras;
// it follows the scene camera (fixed, on its own path, or mounted on a scene object's node). The left camera
// is the reference view of every ground-truth image.
#pragma once

#include "world/camera.h"
#include "scene/objects.h"
#include "scene/sensor_model.h"

#include <string>
#include <vector>

namespace sward {

class Ground;
struct Scene;

struct RigParams {
    double baseline = 0.12;          // metres between the optical centres; 0 = a single camera (no right view)
    double minDepth = 1.0;           // nearest planar depth (m) the stereo search must cover: calib.txt ndisp
    double focalLengthPx = 0.0;      // fx = fy in pixels; 0 = from the vertical field of view
    bool hasPrincipalPoint = false;  // default: the image centre
    glm::dvec2 principalPoint{0.0};  // cx, cy in pixels (pixel centres at +0.5, camera.h)
    std::string mountObject;         // non-empty: the rig rides on this scene object ...
    std::string mountNode;           // ... at this node of its model (its frame: -y forward, +x left, +z up)
    glm::dvec3 mountOffset{0.0};     // rig centre in the node's frame, metres
    double mountPitchDegrees = 10.0; // downward tilt of a mounted rig
    SensorParams sensor;             // colour-only sensor simulation, off by default
    bool stereo() const { return baseline > 0.0; }
    bool mounted() const { return !mountObject.empty(); }
};

struct RigCameras {
    Camera left, right; // right == left when the rig is not stereo
};

// The rig at simulation time `time` for images of width x height pixels. `models` are the scene objects' models
// (loadObjectModels), needed only for a mounted rig.
RigCameras sceneRig(const Scene& scene, const Ground& terrain, const std::vector<ObjectModel>& models,
                    uint32_t width, uint32_t height, double time);

// Disparity in pixels of planar depth z (0 where z is not finite or not positive): f * B / z.
inline float disparityOf(double focalPx, double baseline, float z) {
    return (z > 0.0f && z < 3.0e38f) ? float(focalPx * baseline / double(z)) : 0.0f;
}

} // namespace sward

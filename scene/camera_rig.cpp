#include "scene/camera_rig.h"

#include "common/error.h"
#include "scene/scene.h"

#include <cmath>
#include <numbers>

namespace sward {

namespace {

// Orientation and position of the rig centre: what the scene's camera description gives.
Camera rigCentre(const Scene& scene, const Ground& terrain, const std::vector<ObjectModel>& models, uint32_t width,
                 uint32_t height, double time) {
    const CameraParams& c = scene.camera;
    const RigParams& rig = c.rig;
    if (!rig.mounted()) return sceneCamera(scene, terrain, width, height, time);
    size_t k = 0;
    while (k < scene.objects.size() && scene.objects[k].name != rig.mountObject) ++k;
    require(k < scene.objects.size() && k < models.size(),
            scene.source + ": 'camera.mount.object' names no scene object: '" + rig.mountObject + "'");
    glm::dmat4 node = objectNodeToWorld(scene.objects[k], models[k], rig.mountNode, terrain, time);
    glm::dvec3 position = glm::dvec3(node * glm::dvec4(rig.mountOffset, 1.0));
    // Node frame: -y forward, +x left, +z up (objects.h); pitch the view down about the left axis.
    glm::dvec3 forward = glm::normalize(glm::dvec3(node * glm::dvec4(0, -1, 0, 0)));
    glm::dvec3 up = glm::normalize(glm::dvec3(node * glm::dvec4(0, 0, 1, 0)));
    const double pitch = rig.mountPitchDegrees * std::numbers::pi / 180.0;
    glm::dvec3 view = forward * std::cos(pitch) - up * std::sin(pitch);
    return Camera::lookAt(position, position + view, up, c.fovYDegrees, width, height);
}

} // namespace

RigCameras sceneRig(const Scene& scene, const Ground& terrain, const std::vector<ObjectModel>& models,
                    uint32_t width, uint32_t height, double time) {
    const RigParams& rig = scene.camera.rig;
    Camera centre = rigCentre(scene, terrain, models, width, height, time);
    if (rig.focalLengthPx > 0.0) centre.fx = centre.fy = rig.focalLengthPx;
    if (rig.hasPrincipalPoint) {
        centre.cx = rig.principalPoint.x;
        centre.cy = rig.principalPoint.y;
    }
    RigCameras cameras{centre, centre};
    if (rig.stereo()) {
        glm::dvec3 right = centre.worldFromCamera[0];
        cameras.left.position = centre.position - 0.5 * rig.baseline * right;
        cameras.right.position = centre.position + 0.5 * rig.baseline * right;
    }
    return cameras;
}

} // namespace sward

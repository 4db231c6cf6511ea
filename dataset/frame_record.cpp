#include "dataset/frame_record.h"

#include "scene/scene.h"

namespace sward {

namespace {

nlohmann::json vec3Json(glm::vec3 v) { return {v.x, v.y, v.z}; }

} // namespace

nlohmann::json datasetUnits() {
    return {{"length", "metre"},   {"depth", "metre"}, {"disparity", "pixel"},  {"time", "second"},
            {"baseline", "metre (calib.txt: millimetre)"}, {"angle", "degree"}, {"colour", "linear HDR, arbitrary"}};
}

nlohmann::json datasetConventions() {
    return {{"world_axes", "right-handed, z up"},
            {"camera_axes", "OpenCV: x right, y down, z forward"},
            {"pose", "4x4 camera-to-world, row-major (frames.jsonl left_pose, right_pose)"},
            {"pixel_centres", "whole coordinates: pixel (u, v) has its centre at (u, v) in calib.txt / frames.jsonl"},
            {"image_rows", "top row first (PFM: bottom row first, as the format stores it)"},
            {"depth", "planar camera z of the surface; +inf for sky"},
            {"disparity", "f * B / Z of the left (reference) view; left x - d = right x; sky 0 (PFM +inf, KITTI 0)"},
            {"normal", "unit geometric normal of the drawn triangle in camera axes (both views share them), facing "
                       "the camera (n . view ray < 0); EXR R, G, B = x, y, z; sky 0, 0, 0"},
            {"rig", "rectified: identical intrinsics and orientation, right = left + baseline along camera x"},
            {"frame_time", "frame i shows simulation tick i, time i * sequence.time_step"},
            {"classes", "classes.json"}};
}

nlohmann::json matrixJson(const glm::dmat4& m) {
    nlohmann::json rows = nlohmann::json::array();
    for (int r = 0; r < 4; ++r) rows.push_back({m[0][r], m[1][r], m[2][r], m[3][r]});
    return rows;
}

nlohmann::json cameraPoseJson(const Camera& camera) {
    glm::dmat4 m(camera.worldFromCamera);
    m[3] = glm::dvec4(camera.position, 1.0);
    return matrixJson(m);
}

nlohmann::json colliderJson(const Collider& c) {
    static const char* shapes[] = {"sphere", "capsule", "box"};
    static const char* kinds[] = {"push", "gust", "downwash", "mower"};
    nlohmann::json j = {{"id", c.id}, {"shape", shapes[uint32_t(c.shape)]}, {"kind", kinds[uint32_t(c.kind)]},
                        {"centre", vec3Json(c.centre)}, {"force", c.force}};
    if (c.shape == ColliderShape::Capsule) j["end"] = vec3Json(c.end);
    if (c.shape != ColliderShape::Box) {
        j["radius"] = c.radius;
    } else {
        j["half_extents"] = vec3Json(c.halfExtents);
        j["rotation"] = {vec3Json(c.rotation[0]), vec3Json(c.rotation[1]), vec3Json(c.rotation[2])};
    }
    if (c.kind == ColliderKind::Mower) j["cut_height"] = c.cutHeight;
    return j;
}

nlohmann::json rangeSensorsJson(const Scene& scene, const std::vector<ObjectModel>& models, const Ground& terrain,
                                double time) {
    static const char* kTypes[] = {"lidar", "scanner", "tof"};
    nlohmann::json sensors = nlohmann::json::array();
    for (const RangeSensorParams& s : scene.rangeSensors) {
        const double duration = columnTime(s, s.columns() - 1);
        sensors.push_back({{"name", s.name},
                           {"type", kTypes[int(s.type)]},
                           {"sweep_start", time},
                           {"sweep_duration", duration},
                           {"start_pose", matrixJson(rangeSensorPose(scene, s, terrain, models, time))},
                           {"end_pose", matrixJson(rangeSensorPose(scene, s, terrain, models, time + duration))}});
    }
    return sensors;
}

nlohmann::json frameRecord(const Scene& scene, const std::vector<ObjectModel>& models, const Ground& terrain,
                           const RigCameras& rig, uint32_t frame, double windTimeOffset,
                           std::span<const Collider> acting) {
    const double time = double(frame) * scene.sequence.timeStep;
    nlohmann::json colliders = nlohmann::json::array();
    for (const Collider& c : acting) colliders.push_back(colliderJson(c));
    nlohmann::json objects = nlohmann::json::array();
    for (size_t k = 0; k < scene.objects.size() && k < models.size(); ++k)
        objects.push_back({{"name", scene.objects[k].name},
                           {"instance", objectInstanceId(k)},
                           {"pose", matrixJson(objectPose(scene.objects[k], models[k], terrain, time).worldFromModel)}});
    const WindParams& w = scene.wind;
    const Camera& left = rig.left;
    nlohmann::json record = {
        {"frame", frame},
        {"tick", frame},
        {"time", time},
        {"wind_time", windTimeOffset + time},
        {"left_pose", cameraPoseJson(left)},
        // OpenCV convention (pixel centres at whole coordinates), as in calib.txt
        {"intrinsics", {{"fx", left.fx}, {"fy", left.fy}, {"cx", left.cx - 0.5}, {"cy", left.cy - 0.5},
                        {"width", left.width}, {"height", left.height}}},
        {"wind", {{"direction_deg", w.directionDegrees}, {"strength", w.strength}, {"gust_strength", w.gustStrength},
                  {"gust_frequency", w.gustFrequency}, {"gust_wavelength", w.gustWavelength}, {"flutter", w.flutter}}},
        {"colliders", colliders},
        {"objects", objects}};
    const RigParams& params = scene.camera.rig;
    if (params.stereo()) {
        record["right_pose"] = cameraPoseJson(rig.right);
        record["baseline"] = params.baseline;
    }
    if (params.sensor.enabled) record["sensor"] = sensorToJson(params.sensor);
    if (!scene.rangeSensors.empty()) record["range_sensors"] = rangeSensorsJson(scene, models, terrain, time);
    return record;
}

} // namespace sward

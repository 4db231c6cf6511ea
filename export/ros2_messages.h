// The ROS 2 messages of sward-export --layout ros2, CDR-encoded (export/cdr.h) exactly as rclcpp serialises them,
// and their complete definitions in rosbag2's "ros2msg" form (docs: rosbag2 message_definition_encoding.md): the
// type's .msg text first, then every type it uses, each after a line of 80 '=' and "MSG: package/Type".
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sward {

enum class RosType { Image, CameraInfo, PointCloud2, LaserScan, TFMessage, Odometry };

// "sensor_msgs/msg/Image", ...
const char* rosTypeName(RosType type);
// The complete definition: the type's fields, then each nested type's once (std_msgs/Header, ...).
std::string rosDefinition(RosType type);

// std_msgs/Header: builtin_interfaces/Time from nanoseconds of the simulation clock, and the frame id.
struct RosHeader {
    uint64_t stampNs = 0;
    std::string frameId;
};

// sensor_msgs/Image: `data` is height rows of `step` bytes, top row first, little-endian.
std::string encodeImage(const RosHeader& header, uint32_t width, uint32_t height, std::string_view encoding,
                        uint32_t step, std::string_view data);

struct RosCameraInfo {
    RosHeader header;
    uint32_t width = 0, height = 0;
    std::string distortionModel; // "plumb_bob": d = k1, k2, p1, p2, k3
    std::vector<double> d;
    std::array<double, 9> k{}, r{};
    std::array<double, 12> p{};
};
std::string encodeCameraInfo(const RosCameraInfo& info);

// sensor_msgs/PointField: datatype is one of its constants (INT8 = 1 ... FLOAT64 = 8).
struct RosPointField {
    std::string name;
    uint32_t offset = 0;
    uint8_t datatype = 0;
};
// sensor_msgs/PointCloud2 of one row of `width` points, `pointStep` bytes each, little-endian, dense.
std::string encodePointCloud2(const RosHeader& header, uint32_t width, const std::vector<RosPointField>& fields,
                              uint32_t pointStep, std::string_view data);

struct RosLaserScan {
    RosHeader header;
    float angleMin = 0, angleMax = 0, angleIncrement = 0, timeIncrement = 0, scanTime = 0, rangeMin = 0, rangeMax = 0;
    std::vector<float> ranges, intensities;
};
std::string encodeLaserScan(const RosLaserScan& scan);

// geometry_msgs/TransformStamped: `pose` is parent-from-child (a rigid transform), written as translation and
// unit quaternion.
struct RosTransform {
    RosHeader header; // the parent frame
    std::string childFrameId;
    glm::dmat4 pose{1.0};
};
std::string encodeTfMessage(const std::vector<RosTransform>& transforms);

// nav_msgs/Odometry: the pose of child in header's frame and the twist in the child's frame; covariances 0
// (exact ground truth).
struct RosOdometry {
    RosHeader header;
    std::string childFrameId;
    glm::dmat4 pose{1.0};
    glm::dvec3 linear{0.0}, angular{0.0};
};
std::string encodeOdometry(const RosOdometry& odometry);

} // namespace sward

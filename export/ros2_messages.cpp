#include "export/ros2_messages.h"

#include "export/camera_models.h"
#include "export/cdr.h"

#include <cassert>
#include <cmath>
#include <set>
#include <span>

namespace sward {

namespace {

// One .msg file of ROS 2 (Humble's common_interfaces, comments left out) and the types its fields use.
struct MsgFile {
    const char* name;
    const char* text;
    std::vector<const char*> uses;
};

const std::vector<MsgFile>& msgFiles() {
    static const std::vector<MsgFile> files = {
        {"builtin_interfaces/msg/Time", "int32 sec\nuint32 nanosec\n", {}},
        {"std_msgs/msg/Header", "builtin_interfaces/Time stamp\nstring frame_id\n", {"builtin_interfaces/msg/Time"}},
        {"sensor_msgs/msg/Image",
         "std_msgs/Header header\nuint32 height\nuint32 width\nstring encoding\nuint8 is_bigendian\nuint32 step\n"
         "uint8[] data\n",
         {"std_msgs/msg/Header"}},
        {"sensor_msgs/msg/RegionOfInterest",
         "uint32 x_offset\nuint32 y_offset\nuint32 height\nuint32 width\nbool do_rectify\n",
         {}},
        {"sensor_msgs/msg/CameraInfo",
         "std_msgs/Header header\nuint32 height\nuint32 width\nstring distortion_model\nfloat64[] d\nfloat64[9] k\n"
         "float64[9] r\nfloat64[12] p\nuint32 binning_x\nuint32 binning_y\nsensor_msgs/RegionOfInterest roi\n",
         {"std_msgs/msg/Header", "sensor_msgs/msg/RegionOfInterest"}},
        {"sensor_msgs/msg/PointField",
         "uint8 INT8    = 1\nuint8 UINT8   = 2\nuint8 INT16   = 3\nuint8 UINT16  = 4\nuint8 INT32   = 5\n"
         "uint8 UINT32  = 6\nuint8 FLOAT32 = 7\nuint8 FLOAT64 = 8\nstring name\nuint32 offset\nuint8 datatype\n"
         "uint32 count\n",
         {}},
        {"sensor_msgs/msg/PointCloud2",
         "std_msgs/Header header\nuint32 height\nuint32 width\nsensor_msgs/PointField[] fields\nbool is_bigendian\n"
         "uint32 point_step\nuint32 row_step\nuint8[] data\nbool is_dense\n",
         {"std_msgs/msg/Header", "sensor_msgs/msg/PointField"}},
        {"sensor_msgs/msg/LaserScan",
         "std_msgs/Header header\nfloat32 angle_min\nfloat32 angle_max\nfloat32 angle_increment\n"
         "float32 time_increment\nfloat32 scan_time\nfloat32 range_min\nfloat32 range_max\nfloat32[] ranges\n"
         "float32[] intensities\n",
         {"std_msgs/msg/Header"}},
        {"geometry_msgs/msg/Vector3", "float64 x\nfloat64 y\nfloat64 z\n", {}},
        {"geometry_msgs/msg/Point", "float64 x\nfloat64 y\nfloat64 z\n", {}},
        {"geometry_msgs/msg/Quaternion", "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n", {}},
        {"geometry_msgs/msg/Transform",
         "geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation\n",
         {"geometry_msgs/msg/Vector3", "geometry_msgs/msg/Quaternion"}},
        {"geometry_msgs/msg/TransformStamped",
         "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/Transform transform\n",
         {"std_msgs/msg/Header", "geometry_msgs/msg/Transform"}},
        {"tf2_msgs/msg/TFMessage",
         "geometry_msgs/TransformStamped[] transforms\n",
         {"geometry_msgs/msg/TransformStamped"}},
        {"geometry_msgs/msg/Pose",
         "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n",
         {"geometry_msgs/msg/Point", "geometry_msgs/msg/Quaternion"}},
        {"geometry_msgs/msg/PoseWithCovariance",
         "geometry_msgs/Pose pose\nfloat64[36] covariance\n",
         {"geometry_msgs/msg/Pose"}},
        {"geometry_msgs/msg/Twist",
         "geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular\n",
         {"geometry_msgs/msg/Vector3"}},
        {"geometry_msgs/msg/TwistWithCovariance",
         "geometry_msgs/Twist twist\nfloat64[36] covariance\n",
         {"geometry_msgs/msg/Twist"}},
        {"nav_msgs/msg/Odometry",
         "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n"
         "geometry_msgs/TwistWithCovariance twist\n",
         {"std_msgs/msg/Header", "geometry_msgs/msg/PoseWithCovariance", "geometry_msgs/msg/TwistWithCovariance"}},
    };
    return files;
}

const MsgFile& msgFile(std::string_view name) {
    for (const MsgFile& file : msgFiles())
        if (name == file.name) return file;
    assert(false && "a message type without its .msg text");
    return msgFiles().front();
}

// The nested types of `name`, depth first, each once.
void appendUses(std::string_view name, std::set<std::string_view>& seen, std::string& out) {
    for (const char* used : msgFile(name).uses) {
        if (!seen.insert(used).second) continue;
        // Named as the fields name it ("std_msgs/Header", as rosbag2's Humble writer does), so readers that
        // match a field's type to a definition by name find it.
        std::string name = used;
        name.erase(name.find("/msg/"), 4);
        out += std::string(80, '=') + "\nMSG: " + name + "\n" + msgFile(used).text;
        appendUses(used, seen, out);
    }
}

void putHeader(CdrWriter& cdr, const RosHeader& header) {
    // builtin_interfaces/Time: whole seconds and the nanoseconds beyond them.
    cdr.put(int32_t(header.stampNs / 1000000000u)).put(uint32_t(header.stampNs % 1000000000u));
    cdr.string(header.frameId);
}

void putDoubles(CdrWriter& cdr, std::span<const double> values) {
    cdr.putArray(values);
}

// geometry_msgs/Quaternion (x, y, z, w) of a rotation; camera_models.h gives it as (w, x, y, z).
void putQuaternion(CdrWriter& cdr, const glm::dmat3& rotation) {
    const glm::dvec4 q = rotationQuaternion(rotation);
    cdr.put(q.y).put(q.z).put(q.w).put(q.x);
}

} // namespace

const char* rosTypeName(RosType type) {
    switch (type) {
    case RosType::Image:
        return "sensor_msgs/msg/Image";
    case RosType::CameraInfo:
        return "sensor_msgs/msg/CameraInfo";
    case RosType::PointCloud2:
        return "sensor_msgs/msg/PointCloud2";
    case RosType::LaserScan:
        return "sensor_msgs/msg/LaserScan";
    case RosType::TFMessage:
        return "tf2_msgs/msg/TFMessage";
    case RosType::Odometry:
        return "nav_msgs/msg/Odometry";
    }
    return "";
}

std::string rosDefinition(RosType type) {
    const MsgFile& top = msgFile(rosTypeName(type));
    std::string text = top.text;
    std::set<std::string_view> seen;
    appendUses(top.name, seen, text);
    return text;
}

std::string encodeImage(const RosHeader& header, uint32_t width, uint32_t height, std::string_view encoding,
                        uint32_t step, std::string_view data) {
    assert(data.size() == size_t(step) * height);
    CdrWriter cdr;
    putHeader(cdr, header);
    cdr.put(height).put(width).string(encoding).put(uint8_t(0)).put(step).byteSequence(data);
    return cdr.bytes();
}

std::string encodeCameraInfo(const RosCameraInfo& info) {
    CdrWriter cdr;
    putHeader(cdr, info.header);
    cdr.put(info.height).put(info.width).string(info.distortionModel).sequenceLength(info.d.size());
    putDoubles(cdr, info.d);
    putDoubles(cdr, info.k);
    putDoubles(cdr, info.r);
    putDoubles(cdr, info.p);
    cdr.put(uint32_t(0)).put(uint32_t(0));                                   // binning: none
    cdr.put(uint32_t(0)).put(uint32_t(0)).put(uint32_t(0)).put(uint32_t(0)); // roi: the whole image
    cdr.put(uint8_t(0));                                                     // roi.do_rectify
    return cdr.bytes();
}

std::string encodePointCloud2(const RosHeader& header, uint32_t width, const std::vector<RosPointField>& fields,
                              uint32_t pointStep, std::string_view data) {
    assert(data.size() == size_t(pointStep) * width);
    CdrWriter cdr;
    putHeader(cdr, header);
    cdr.put(uint32_t(1)).put(width).sequenceLength(fields.size());
    for (const RosPointField& field : fields)
        cdr.string(field.name).put(field.offset).put(field.datatype).put(uint32_t(1));
    cdr.put(uint8_t(0)).put(pointStep).put(uint32_t(pointStep * width)).byteSequence(data);
    cdr.put(uint8_t(1)); // is_dense: every point is a return
    return cdr.bytes();
}

std::string encodeLaserScan(const RosLaserScan& scan) {
    CdrWriter cdr;
    putHeader(cdr, scan.header);
    cdr.put(scan.angleMin).put(scan.angleMax).put(scan.angleIncrement).put(scan.timeIncrement).put(scan.scanTime);
    cdr.put(scan.rangeMin).put(scan.rangeMax);
    cdr.sequenceLength(scan.ranges.size()).putArray(std::span<const float>(scan.ranges));
    cdr.sequenceLength(scan.intensities.size()).putArray(std::span<const float>(scan.intensities));
    return cdr.bytes();
}

std::string encodeTfMessage(const std::vector<RosTransform>& transforms) {
    CdrWriter cdr;
    cdr.sequenceLength(transforms.size());
    for (const RosTransform& t : transforms) {
        putHeader(cdr, t.header);
        cdr.string(t.childFrameId);
        cdr.put(t.pose[3].x).put(t.pose[3].y).put(t.pose[3].z);
        putQuaternion(cdr, glm::dmat3(t.pose));
    }
    return cdr.bytes();
}

std::string encodeOdometry(const RosOdometry& odometry) {
    CdrWriter cdr;
    putHeader(cdr, odometry.header);
    cdr.string(odometry.childFrameId);
    const glm::dvec3 p = odometry.pose[3];
    const std::array<double, 36> covariance{};
    cdr.put(p.x).put(p.y).put(p.z);
    putQuaternion(cdr, glm::dmat3(odometry.pose));
    putDoubles(cdr, covariance);
    cdr.put(odometry.linear.x).put(odometry.linear.y).put(odometry.linear.z);
    cdr.put(odometry.angular.x).put(odometry.angular.y).put(odometry.angular.z);
    putDoubles(cdr, covariance);
    return cdr.bytes();
}

} // namespace sward

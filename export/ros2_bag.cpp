#include "export/ros2_bag.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/input_file.h"
#include "dataset/naming.h"
#include "export/mcap_writer.h"
#include "export/ros2_messages.h"
#include "io/image_io.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace sward {

namespace {

constexpr const char* kWorldFrame = "world";
constexpr const char* kLeftFrame = "left_camera_optical";
constexpr const char* kRightFrame = "right_camera_optical";
// The offered QoS rosbag2 (Humble) records for a publisher with rclcpp's defaults: reliable, volatile, keep last.
// ros2 bag play offers the same again.
constexpr const char* kQosProfiles =
    "- history: 3\n  depth: 0\n  reliability: 1\n  durability: 2\n  deadline:\n    sec: 9223372036\n"
    "    nsec: 854775807\n  lifespan:\n    sec: 9223372036\n    nsec: 854775807\n  liveliness: 1\n"
    "  liveliness_lease_duration:\n    sec: 9223372036\n    nsec: 854775807\n  avoid_ros_namespace_conventions: false";
constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;

struct RangeRecord {
    std::string name, type;
    uint64_t sweepStartNs = 0;
    double sweepDuration = 0;
    glm::dmat4 startPose{1.0};
};
struct ObjectRecord {
    std::string name;
    glm::dmat4 pose{1.0};
};
// What the bag takes from one record of frames.jsonl.
struct BagFrame {
    double time = 0;
    uint64_t timeNs = 0;
    glm::dmat4 left{1.0}, right{1.0};
    std::vector<ObjectRecord> objects;
    std::vector<RangeRecord> sensors;
};

glm::dmat4 poseOf(const nlohmann::json& rows) {
    glm::dmat4 m(1.0);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) m[c][r] = rows.at(r).at(c).get<double>();
    return m;
}

// A ROS 2 stamp holds int32 seconds; the simulation clock starts at 0.
uint64_t nanoseconds(double seconds, const std::string& where) {
    require(std::isfinite(seconds) && seconds >= 0.0 && seconds < 2147483647.0,
            where + ": time " + std::to_string(seconds) + " s does not fit a ROS 2 stamp (0 .. 2^31 s)");
    return uint64_t(std::llround(seconds * 1e9));
}

// A name as a ROS 2 topic or frame token: letters, digits and '_' (anything else becomes '_'), not starting
// with a digit.
std::string rosName(const std::string& name) {
    std::string out = name.empty() ? "_" : name;
    for (char& c : out)
        if (!std::isalnum(uint8_t(c)) && c != '_') c = '_';
    return std::isdigit(uint8_t(out[0])) ? "_" + out : out;
}

BagFrame parseBagFrame(const nlohmann::json& record, const std::string& where) {
    BagFrame frame{.time = record.at("time").get<double>(), .left = poseOf(record.at("left_pose"))};
    frame.timeNs = nanoseconds(frame.time, where);
    if (record.contains("right_pose")) frame.right = poseOf(record.at("right_pose"));
    for (const nlohmann::json& object : record.value("objects", nlohmann::json::array()))
        frame.objects.push_back({rosName(object.at("name").get<std::string>()), poseOf(object.at("pose"))});
    for (const nlohmann::json& sensor : record.value("range_sensors", nlohmann::json::array()))
        frame.sensors.push_back({.name = sensor.at("name").get<std::string>(),
                                 .type = sensor.at("type").get<std::string>(),
                                 .sweepStartNs = nanoseconds(sensor.at("sweep_start").get<double>(), where),
                                 .sweepDuration = sensor.at("sweep_duration").get<double>(),
                                 .startPose = poseOf(sensor.at("start_pose"))});
    return frame;
}

// Every record of frames.jsonl, in frame order (openExportDataset has checked the numbering).
std::vector<BagFrame> readBagFrames(const std::string& dir) {
    const std::string path = dir + "/" + kFrameLogFile;
    std::istringstream file(readInputFile(path, "frame log"));
    std::vector<BagFrame> frames;
    for (std::string line; std::getline(file, line);) {
        const std::string where = path + " line " + std::to_string(frames.size() + 1);
        try {
            frames.push_back(parseBagFrame(nlohmann::json::parse(line), where));
        } catch (const nlohmann::json::exception& e) {
            throw Error(where + ": not a sward frame record (" + e.what() + ")");
        }
    }
    return frames;
}

// The bag's channels, made on first use (one schema per message type), and what metadata.yaml counts.
class BagWriter {
public:
    explicit BagWriter(const std::string& path) : mcap_(path, "ros2", "sward-export") {}

    void publish(const std::string& topic, RosType type, uint64_t logTime, const std::string& message) {
        auto it = channels_.find(topic);
        if (it == channels_.end()) {
            if (!schemas_.count(type))
                schemas_[type] = mcap_.addSchema(rosTypeName(type), "ros2msg", rosDefinition(type));
            const uint16_t id =
                mcap_.addChannel(schemas_[type], topic, "cdr", {{"offered_qos_profiles", kQosProfiles}});
            it = channels_.emplace(topic, topics_.size()).first;
            topics_.push_back({topic, type, id, 0});
        }
        mcap_.addMessage(topics_[it->second].channel, logTime, logTime, message);
        ++topics_[it->second].count;
        first_ = std::min(first_, logTime), last_ = std::max(last_, logTime);
    }
    void endFrame() { mcap_.flushChunk(); }
    // Finishes the MCAP file and returns metadata.yaml's text.
    std::string finish();

private:
    struct Topic {
        std::string name;
        RosType type;
        uint16_t channel;
        uint64_t count;
    };
    McapWriter mcap_;
    std::map<RosType, uint16_t> schemas_;
    std::map<std::string, size_t> channels_; // topic -> index in topics_
    std::vector<Topic> topics_;
    uint64_t first_ = UINT64_MAX, last_ = 0;
};

std::string BagWriter::finish() {
    mcap_.finish();
    uint64_t count = 0;
    for (const Topic& t : topics_) count += t.count;
    const std::string start = std::to_string(count ? first_ : 0), duration = std::to_string(count ? last_ - first_ : 0);
    std::string qos = nlohmann::json(kQosProfiles).dump(); // a YAML double-quoted scalar, as rosbag2 writes it
    std::string yaml = "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: mcap\n  duration:\n"
                       "    nanoseconds: " +
                       duration + "\n  starting_time:\n    nanoseconds_since_epoch: " + start +
                       "\n  message_count: " + std::to_string(count) + "\n  topics_with_message_count:\n";
    for (const Topic& t : topics_)
        yaml += "    - topic_metadata:\n        name: " + t.name + "\n        type: " + rosTypeName(t.type) +
                "\n        serialization_format: cdr\n        offered_qos_profiles: " + qos +
                "\n      message_count: " + std::to_string(t.count) + "\n";
    yaml += std::string("  compression_format: \"\"\n  compression_mode: \"\"\n  relative_file_paths:\n    - ") +
            kRos2BagFile + "\n  files:\n    - path: " + kRos2BagFile + "\n      starting_time:\n" +
            "        nanoseconds_since_epoch: " + start + "\n      duration:\n        nanoseconds: " + duration +
            "\n      message_count: " + std::to_string(count) + "\n";
    return yaml;
}

// An image of the dataset as a ROS image's data: 8-bit PNGs as their bytes, EXRs as little-endian float32.
std::string imageData(const ExportDataset& dataset, const char* folder, uint32_t frame, const char* extension,
                      uint32_t channels) {
    const std::string path = dataset.dir + "/" + frameFile(folder, frame, extension);
    const ImageData image = loadImage(path);
    require(image.width == dataset.camera.width && image.height == dataset.camera.height && image.channels == channels,
            path + ": " + std::to_string(image.width) + "x" + std::to_string(image.height) + " with " +
                std::to_string(image.channels) + " channel(s), expected " + std::to_string(dataset.camera.width) + "x" +
                std::to_string(dataset.camera.height) + " with " + std::to_string(channels) + " (frames.jsonl)");
    std::string data;
    if (std::string_view(extension) == ".png") {
        require(image.bitDepth == 8, path + ": " + std::to_string(image.bitDepth) + "-bit, expected an 8-bit PNG");
        data.resize(image.samples.size());
        // PNG samples come normalised to [0, 1]: 8-bit values are exact multiples of 1/255.
        for (size_t i = 0; i < data.size(); ++i) data[i] = char(uint8_t(std::lround(image.samples[i] * 255.0f)));
    } else {
        data.resize(image.samples.size() * sizeof(float));
        std::memcpy(data.data(), image.samples.data(), data.size());
    }
    return data;
}

RosCameraInfo cameraInfo(const ExportCamera& camera, const RosHeader& header, double tx, bool distorted) {
    RosCameraInfo info{
        .header = header, .width = camera.width, .height = camera.height, .distortionModel = "plumb_bob"};
    info.d.assign(5, 0.0);
    if (distorted) info.d.assign(camera.distortion.begin(), camera.distortion.end());
    info.k = {camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1};
    info.r = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    // ROS's stereo convention: the right camera's P carries Tx = -fx * baseline.
    info.p = {camera.fx, 0, camera.cx, tx, 0, camera.fy, camera.cy, 0, 0, 0, 1, 0};
    return info;
}

void publishCameras(BagWriter& bag, const ExportDataset& dataset, uint32_t frame, uint64_t t) {
    const ExportCamera& camera = dataset.camera;
    const uint32_t w = camera.width, h = camera.height;
    const RosHeader left{t, kLeftFrame}, right{t, kRightFrame};
    bag.publish("/sward/left/image_raw", RosType::Image, t,
                encodeImage(left, w, h, "rgb8", 3 * w, imageData(dataset, kPreviewFolder, frame, ".png", 3)));
    bag.publish("/sward/left/camera_info", RosType::CameraInfo, t,
                encodeCameraInfo(cameraInfo(camera, left, 0.0, true)));
    bag.publish("/sward/left/depth/image_rect", RosType::Image, t,
                encodeImage(left, w, h, "32FC1", 4 * w, imageData(dataset, kDepthFolder, frame, ".exr", 1)));
    // The ground truth is never distorted (scene/sensor_model.h), whatever the colour images are.
    bag.publish("/sward/left/depth/camera_info", RosType::CameraInfo, t,
                encodeCameraInfo(cameraInfo(camera, left, 0.0, false)));
    if (!dataset.stereo) return;
    bag.publish("/sward/right/image_raw", RosType::Image, t,
                encodeImage(right, w, h, "rgb8", 3 * w, imageData(dataset, kPreviewRightFolder, frame, ".png", 3)));
    bag.publish("/sward/right/camera_info", RosType::CameraInfo, t,
                encodeCameraInfo(cameraInfo(camera, right, -camera.fx * camera.baseline, true)));
}

// A binary little-endian PLY's vertices as a PointCloud2's fields and data (range/range_files.h wrote it).
struct PlyVertices {
    std::vector<RosPointField> fields;
    uint32_t count = 0, stride = 0;
    std::string_view data;
};

uint8_t pointFieldType(const std::string& plyType) {
    static const std::map<std::string, uint8_t> types = {{"char", 1},  {"int8", 1},    {"uchar", 2},  {"uint8", 2},
                                                         {"short", 3}, {"int16", 3},   {"ushort", 4}, {"uint16", 4},
                                                         {"int", 5},   {"int32", 5},   {"uint", 6},   {"uint32", 6},
                                                         {"float", 7}, {"float32", 7}, {"double", 8}, {"float64", 8}};
    const auto it = types.find(plyType);
    return it == types.end() ? 0 : it->second;
}

PlyVertices parsePlyVertices(const std::string& bytes, const std::string& path) {
    const size_t end = bytes.find("end_header\n");
    require(bytes.starts_with("ply\nformat binary_little_endian 1.0\n") && end != std::string::npos,
            path + ": not a binary little-endian PLY");
    std::istringstream header(bytes.substr(0, end));
    PlyVertices ply;
    for (std::string line; std::getline(header, line);) {
        std::istringstream words(line);
        std::string keyword, type, name;
        words >> keyword >> type >> name;
        if (keyword == "element") {
            require(type == "vertex" && ply.fields.empty(), path + ": an element other than vertex");
            ply.count = uint32_t(std::stoul(name));
        } else if (keyword == "property") {
            const uint8_t datatype = pointFieldType(type);
            require(datatype != 0, path + ": property type '" + type + "' has no PointField type");
            // sward's LiDAR names the semantic class "class"; ROS point clouds call it "label".
            ply.fields.push_back({name == "class" ? "label" : name, ply.stride, datatype});
            constexpr uint32_t kSizes[] = {0, 1, 1, 2, 2, 4, 4, 4, 8}; // by PointField datatype
            ply.stride += kSizes[datatype];
        }
    }
    ply.data = std::string_view(bytes).substr(end + 11);
    require(ply.data.size() == size_t(ply.count) * ply.stride,
            path + ": " + std::to_string(ply.data.size()) + " bytes of vertices, expected " +
                std::to_string(ply.count) + " x " + std::to_string(ply.stride));
    return ply;
}

RosLaserScan laserScan(const std::string& path, const RangeRecord& sensor) {
    const nlohmann::json scan = nlohmann::json::parse(readInputFile(path, "laser scan"));
    RosLaserScan msg{.header = {sensor.sweepStartNs, rosName(sensor.name)},
                     .angleMin = float(scan.at("angle_min_deg").get<double>() * kRadiansPerDegree),
                     .angleIncrement = float(scan.at("angle_increment_deg").get<double>() * kRadiansPerDegree),
                     .timeIncrement = scan.at("time_increment_s").get<float>(),
                     .scanTime = float(sensor.sweepDuration),
                     .rangeMin = scan.at("range_min").get<float>(),
                     .rangeMax = scan.at("range_max").get<float>()};
    for (const nlohmann::json& range : scan.at("ranges"))
        msg.ranges.push_back(range.is_null() ? std::numeric_limits<float>::infinity() : range.get<float>());
    const double last =
        scan.at("angle_min_deg").get<double>() +
        double(msg.ranges.empty() ? 0 : msg.ranges.size() - 1) * scan.at("angle_increment_deg").get<double>();
    msg.angleMax = float(last * kRadiansPerDegree);
    return msg;
}

void publishRangeSensors(BagWriter& bag, const ExportDataset& dataset, uint32_t frame, const BagFrame& record,
                         uint64_t t) {
    for (const RangeRecord& sensor : record.sensors) {
        const std::string base = dataset.dir + "/" + kRangeFolder + "/" + sensor.name + "/" + frameName(frame);
        const std::string topic = "/sward/range/" + rosName(sensor.name);
        if (sensor.type == "lidar") {
            const std::string bytes = readInputFile(base + ".ply", "LiDAR point cloud");
            const PlyVertices ply = parsePlyVertices(bytes, base + ".ply");
            const RosHeader header{sensor.sweepStartNs, rosName(sensor.name)};
            bag.publish(topic + "/points", RosType::PointCloud2, t,
                        encodePointCloud2(header, ply.count, ply.fields, ply.stride, ply.data));
        } else if (sensor.type == "scanner") {
            try {
                bag.publish(topic + "/scan", RosType::LaserScan, t, encodeLaserScan(laserScan(base + ".json", sensor)));
            } catch (const nlohmann::json::exception& e) {
                throw Error(base + ".json: not a sward laser scan (" + e.what() + ")");
            }
        } // time-of-flight cameras: their depth stays in the dataset (range/<name>/*.exr)
    }
}

// /tf: the cameras and objects at the frame's time, each range sensor where its sweep starts. `where` names the
// frame's record for the error of two bodies under one frame id (TF could not tell them apart).
void publishTransforms(BagWriter& bag, const ExportDataset& dataset, const BagFrame& record, uint64_t t,
                       const std::string& where) {
    std::vector<RosTransform> transforms{{{t, kWorldFrame}, kLeftFrame, record.left}};
    if (dataset.stereo) transforms.push_back({{t, kWorldFrame}, kRightFrame, record.right});
    for (const ObjectRecord& object : record.objects)
        transforms.push_back({{t, kWorldFrame}, object.name, object.pose});
    for (const RangeRecord& sensor : record.sensors)
        transforms.push_back({{sensor.sweepStartNs, kWorldFrame}, rosName(sensor.name), sensor.startPose});
    std::set<std::string> ids{kWorldFrame};
    for (const RosTransform& transform : transforms)
        require(ids.insert(transform.childFrameId).second,
                where + ": two frames of the ROS 2 bag would be called '" + transform.childFrameId +
                    "' (objects and range sensors are named by their names, cameras left_camera_optical and "
                    "right_camera_optical, the root world); rename one in the scene");
    bag.publish("/tf", RosType::TFMessage, t, encodeTfMessage(transforms));
}

// The velocity between two poses `dt` seconds apart, in the body frame of `from`: linear from the positions,
// angular from the relative rotation R as the axial vector of (R - R^T) / 2, which is sin(angle) * axis: within
// angle^2 / 6 of the exact rate for the small turn of one tick, and no trigonometry.
void finiteTwist(const glm::dmat4& from, const glm::dmat4& to, double dt, RosOdometry& odometry) {
    const glm::dmat3 rotation(from);
    odometry.linear = glm::transpose(rotation) * (glm::dvec3(to[3]) - glm::dvec3(from[3])) / dt;
    const glm::dmat3 r = glm::transpose(rotation) * glm::dmat3(to);
    odometry.angular = glm::dvec3(r[1][2] - r[2][1], r[2][0] - r[0][2], r[0][1] - r[1][0]) * (0.5 / dt);
}

// One body's Odometry at frames[index]: its twist towards the next frame of the sequence (from the previous one
// for the last frame; none for a one-frame sequence). `poseAt` gives the body's pose in a frame, or nullptr.
template <typename PoseAt>
void publishOdometry(BagWriter& bag, const std::vector<BagFrame>& frames, size_t index, const std::string& topic,
                     const std::string& child, PoseAt poseAt) {
    const BagFrame& now = frames[index];
    RosOdometry odometry{.header = {now.timeNs, kWorldFrame}, .childFrameId = child, .pose = *poseAt(now)};
    const size_t a = index + 1 < frames.size() ? index : index - (index > 0);
    const size_t b = index + 1 < frames.size() ? index + 1 : index;
    if (a != b && poseAt(frames[a]) && poseAt(frames[b]) && frames[b].time > frames[a].time)
        finiteTwist(*poseAt(frames[a]), *poseAt(frames[b]), frames[b].time - frames[a].time, odometry);
    bag.publish(topic, RosType::Odometry, now.timeNs, encodeOdometry(odometry));
}

void publishAllOdometry(BagWriter& bag, const std::vector<BagFrame>& frames, size_t index) {
    publishOdometry(bag, frames, index, "/sward/odom/left_camera", kLeftFrame,
                    [](const BagFrame& f) { return &f.left; });
    for (const ObjectRecord& object : frames[index].objects)
        publishOdometry(bag, frames, index, "/sward/odom/" + object.name, object.name,
                        [&](const BagFrame& f) -> const glm::dmat4* {
                            for (const ObjectRecord& o : f.objects)
                                if (o.name == object.name) return &o.pose;
                            return nullptr;
                        });
}

} // namespace

void exportRos2Bag(const ExportDataset& dataset, const std::string& out) {
    const std::vector<BagFrame> frames = readBagFrames(dataset.dir);
    BagWriter bag(out + "/" + kRos2BagFile);
    for (const ExportFrame& f : dataset.frames) {
        require(f.frame < frames.size(),
                dataset.dir + "/" + kFrameLogFile + " has no record of frame " + std::to_string(f.frame));
        const BagFrame& record = frames[f.frame];
        publishTransforms(bag, dataset, record, record.timeNs,
                          dataset.dir + "/" + kFrameLogFile + " frame " + std::to_string(f.frame));
        publishCameras(bag, dataset, f.frame, record.timeNs);
        publishRangeSensors(bag, dataset, f.frame, record, record.timeNs);
        publishAllOdometry(bag, frames, f.frame);
        bag.endFrame(); // one chunk per frame: a player seeks to any frame through the chunk index
    }
    writeTextAtomically(out + "/" + kRos2MetadataFile, bag.finish());
}

} // namespace sward

// sward-export --layout ros2 read back by an independent reader: Foxglove's @mcap/core, @foxglove/rosmsg and
// @foxglove/rosmsg2-serialization under Node.js (mcap/read_bag.mjs; tools/setup-deps.sh installs them from
// mcap/package-lock.json) decode every message of the bag of examples/rover-lidar.json (64x48 stereo, 3 frames, a
// VLP-16 LiDAR, a laser scanner and the rover), and the decoded images, point clouds, scans and transforms equal the
// dataset's own files, read here with OpenCV, a PLY header reader and nlohmann::json. Skipped without Node.js or
// the npm packages.
#include "gpu_test.h"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <sys/wait.h>

using nlohmann::json;
using sward::test::readFile;
using sward::test::tempDir;

namespace {

const std::string kMcapDir = SWARD_TEST_DATA_DIR "/../tools/sward-export/mcap";
const std::string kScene = SWARD_TEST_DATA_DIR "/../../examples/rover-lidar.json";
constexpr int kFrames = 3;

struct Bag {
    std::string dataset, decoded;
    std::vector<json> messages; // in log-time order
    std::vector<json> frames;   // frames.jsonl
    std::string skip;           // why the bag could not be read here, when it could not
    std::vector<json> on(const std::string& topic) const {
        std::vector<json> found;
        for (const json& m : messages)
            if (m["topic"] == topic) found.push_back(m);
        return found;
    }
};

int run(const std::string& command, std::string& err) {
    const std::string errFile = tempDir("ros2-log") + "/err.txt";
    const int status = std::system((command + " >/dev/null 2>" + errFile).c_str());
    err = readFile(errFile);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

const Bag& bag() {
    static const Bag b = [] {
        Bag bag;
        std::string err;
        if (run("node --version", err) != 0) return bag.skip = "no Node.js (tools/setup-deps.sh installs it)", bag;
        if (!std::filesystem::is_directory(kMcapDir + "/node_modules/@mcap/core"))
            return bag.skip = "no " + kMcapDir + "/node_modules (tools/setup-deps.sh runs npm ci there)", bag;
        bag.dataset = tempDir("ros2-dataset");
        EXPECT_EQ(sward::test::runSwardRender(kScene + " --out " + bag.dataset +
                                                  " --resolution 64x48 --frames 0:" + std::to_string(kFrames),
                                              err),
                  0)
            << err;
        const std::string out = tempDir("ros2-bag") + "/bag";
        EXPECT_EQ(run(SWARD_EXPORT_EXE " " + bag.dataset + " --layout ros2 --out " + out, err), 0) << err;
        bag.decoded = tempDir("ros2-decoded");
        EXPECT_EQ(run("node " + kMcapDir + "/read_bag.mjs " + out + "/sward_0.mcap " + bag.decoded, err), 0) << err;
        std::istringstream lines(readFile(bag.decoded + "/messages.jsonl"));
        for (std::string line; std::getline(lines, line);) bag.messages.push_back(json::parse(line));
        std::istringstream frames(readFile(bag.dataset + "/frames.jsonl"));
        for (std::string line; std::getline(frames, line);) bag.frames.push_back(json::parse(line));
        return bag;
    }();
    return b;
}

uint64_t stampNs(const json& header) {
    return header["stamp"]["sec"].get<uint64_t>() * 1000000000u + header["stamp"]["nanosec"].get<uint64_t>();
}
uint64_t frameNs(int frame) {
    return uint64_t(std::llround(bag().frames[frame]["time"].get<double>() * 1e9));
}
std::string frameName(int frame) {
    char name[8];
    std::snprintf(name, sizeof(name), "%06d", frame);
    return name;
}

// A 4x4 row-major pose of frames.jsonl as glm (column-major).
glm::dmat4 pose(const json& rows) {
    glm::dmat4 m(1.0);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) m[c][r] = rows[r][c].get<double>();
    return m;
}

// The rotation of a unit quaternion (x, y, z, w).
glm::dmat3 rotation(const json& q) {
    const double x = q["x"], y = q["y"], z = q["z"], w = q["w"];
    return glm::transpose(glm::dmat3(1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w),
                                     2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
                                     2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)));
}

void expectPose(const json& translation, const json& quaternion, const glm::dmat4& expected, const std::string& what) {
    EXPECT_EQ(translation["x"].get<double>(), expected[3].x) << what;
    EXPECT_EQ(translation["y"].get<double>(), expected[3].y) << what;
    EXPECT_EQ(translation["z"].get<double>(), expected[3].z) << what;
    const glm::dmat3 r = rotation(quaternion);
    for (int c = 0; c < 3; ++c)
        for (int row = 0; row < 3; ++row) EXPECT_NEAR(r[c][row], expected[c][row], 1e-12) << what;
}

std::string bin(const json& field) {
    return readFile(bag().decoded + "/" + field["bin"].get<std::string>());
}

void expectEveryTopicOncePerFrameAtTheSimulationTime() {
    const std::map<std::string, std::string> topics = {{"/tf", "tf2_msgs/msg/TFMessage"},
                                                       {"/sward/left/image_raw", "sensor_msgs/msg/Image"},
                                                       {"/sward/left/camera_info", "sensor_msgs/msg/CameraInfo"},
                                                       {"/sward/left/depth/image_rect", "sensor_msgs/msg/Image"},
                                                       {"/sward/left/depth/camera_info", "sensor_msgs/msg/CameraInfo"},
                                                       {"/sward/right/image_raw", "sensor_msgs/msg/Image"},
                                                       {"/sward/right/camera_info", "sensor_msgs/msg/CameraInfo"},
                                                       {"/sward/range/lidar/points", "sensor_msgs/msg/PointCloud2"},
                                                       {"/sward/range/scanner/scan", "sensor_msgs/msg/LaserScan"},
                                                       {"/sward/odom/left_camera", "nav_msgs/msg/Odometry"},
                                                       {"/sward/odom/rover", "nav_msgs/msg/Odometry"}};
    EXPECT_EQ(bag().messages.size(), topics.size() * kFrames);
    for (const auto& [topic, schema] : topics) {
        const std::vector<json> messages = bag().on(topic);
        ASSERT_EQ(messages.size(), size_t(kFrames)) << topic;
        for (int f = 0; f < kFrames; ++f) {
            EXPECT_EQ(messages[f]["schema"], schema) << topic;
            EXPECT_EQ(messages[f]["sequence"], f) << topic;
            EXPECT_EQ(messages[f]["log_time"], std::to_string(frameNs(f))) << topic;
        }
    }
    EXPECT_EQ(frameNs(2), 200000000u); // rover-lidar's time step is 0.1 s
}

void expectImagesAreThePreviewsAndDepthWithTheirIntrinsics() {
    for (int f = 0; f < kFrames; ++f) {
        const std::string name = frameName(f);
        for (const auto& [topic, folder] :
             {std::pair{"/sward/left/image_raw", "preview"}, std::pair{"/sward/right/image_raw", "preview_right"}}) {
            const json m = bag().on(topic)[f]["message"];
            cv::Mat rgb = cv::imread(bag().dataset + "/" + folder + "/" + name + ".png", cv::IMREAD_COLOR);
            cv::cvtColor(rgb, rgb, cv::COLOR_BGR2RGB);
            EXPECT_EQ(m["encoding"], "rgb8");
            EXPECT_EQ(m["width"], 64);
            EXPECT_EQ(m["height"], 48);
            EXPECT_EQ(m["step"], 64 * 3);
            EXPECT_EQ(stampNs(m["header"]), frameNs(f));
            EXPECT_EQ(bin(m["data"]), std::string(reinterpret_cast<const char*>(rgb.data), rgb.total() * 3)) << topic;
        }
        const json depth = bag().on("/sward/left/depth/image_rect")[f]["message"];
        const cv::Mat z = cv::imread(bag().dataset + "/depth/" + name + ".exr", cv::IMREAD_UNCHANGED);
        ASSERT_EQ(z.type(), CV_32FC1);
        EXPECT_EQ(depth["encoding"], "32FC1");
        EXPECT_EQ(depth["header"]["frame_id"], "left_camera_optical");
        EXPECT_EQ(bin(depth["data"]), std::string(reinterpret_cast<const char*>(z.data), z.total() * 4));
    }
    const json& k = bag().frames[0]["intrinsics"];
    const json left = bag().on("/sward/left/camera_info")[0]["message"];
    const json right = bag().on("/sward/right/camera_info")[0]["message"];
    EXPECT_EQ(left["k"], json({k["fx"], 0, k["cx"], 0, k["fy"], k["cy"], 0, 0, 1}));
    EXPECT_EQ(left["distortion_model"], "plumb_bob");
    EXPECT_EQ(right["header"]["frame_id"], "right_camera_optical");
    EXPECT_EQ(right["p"][3].get<double>(), -k["fx"].get<double>() * bag().frames[0]["baseline"].get<double>());
}

void expectLidarCloudIsThePlysPointsWithRingTimeAndLabel() {
    for (int f = 0; f < kFrames; ++f) {
        const json m = bag().on("/sward/range/lidar/points")[f]["message"];
        const std::string ply = readFile(bag().dataset + "/range/lidar/" + frameName(f) + ".ply");
        const size_t end = ply.find("end_header\n") + 11;
        std::istringstream header(ply.substr(0, end));
        size_t count = 0;
        std::vector<std::string> names;
        for (std::string line; std::getline(header, line);) {
            std::istringstream words(line);
            std::string a, b, c;
            words >> a >> b >> c;
            if (a == "element") count = std::stoul(c);
            if (a == "property") names.push_back(c == "class" ? "label" : c);
        }
        ASSERT_GT(count, 1000u);
        EXPECT_EQ(m["width"], count);
        EXPECT_EQ(m["height"], 1);
        EXPECT_EQ(m["point_step"].get<size_t>() * count, ply.size() - end);
        EXPECT_EQ(bin(m["data"]), ply.substr(end));
        ASSERT_EQ(m["fields"].size(), names.size());
        std::map<std::string, int> types;
        for (size_t i = 0; i < names.size(); ++i) {
            EXPECT_EQ(m["fields"][i]["name"], names[i]);
            types[names[i]] = m["fields"][i]["datatype"];
        }
        // PointField: UINT8 2, UINT16 4, UINT32 6, FLOAT32 7, FLOAT64 8
        EXPECT_EQ(types["x"], 7);
        EXPECT_EQ(types["wx"], 8);
        EXPECT_EQ(types["ring"], 4);
        EXPECT_EQ(types["time"], 7);
        EXPECT_EQ(types["label"], 2);
        EXPECT_EQ(types["instance"], 6);
        EXPECT_EQ(m["header"]["frame_id"], "lidar");
        const json& sensor = bag().frames[f]["range_sensors"][0];
        EXPECT_EQ(stampNs(m["header"]), uint64_t(std::llround(sensor["sweep_start"].get<double>() * 1e9)));
    }
}

void expectScanIsTheScannersRanges() {
    for (int f = 0; f < kFrames; ++f) {
        const json m = bag().on("/sward/range/scanner/scan")[f]["message"];
        const json scan = json::parse(readFile(bag().dataset + "/range/scanner/" + frameName(f) + ".json"));
        ASSERT_EQ(m["ranges"].size(), scan["ranges"].size());
        size_t returns = 0;
        for (size_t i = 0; i < scan["ranges"].size(); ++i) {
            if (scan["ranges"][i].is_null()) {
                EXPECT_EQ(m["ranges"][i], "Infinity") << i;
                continue;
            }
            ++returns;
            EXPECT_EQ(m["ranges"][i].get<float>(), scan["ranges"][i].get<float>()) << i;
        }
        EXPECT_GT(returns, 100u);
        EXPECT_FLOAT_EQ(m["angle_min"].get<float>(), float(scan["angle_min_deg"].get<double>() * M_PI / 180));
        EXPECT_EQ(m["header"]["frame_id"], "scanner");
    }
}

void expectTransformsAndOdometryAreThePoses() {
    for (int f = 0; f < kFrames; ++f) {
        const json& record = bag().frames[f];
        std::map<std::string, glm::dmat4> expected = {{"left_camera_optical", pose(record["left_pose"])},
                                                      {"right_camera_optical", pose(record["right_pose"])},
                                                      {"rover", pose(record["objects"][0]["pose"])}};
        for (const json& sensor : record["range_sensors"]) expected[sensor["name"]] = pose(sensor["start_pose"]);
        const json tf = bag().on("/tf")[f]["message"]["transforms"];
        ASSERT_EQ(tf.size(), expected.size());
        for (const json& t : tf) {
            const std::string child = t["child_frame_id"];
            ASSERT_TRUE(expected.count(child)) << child;
            EXPECT_EQ(t["header"]["frame_id"], "world");
            expectPose(t["transform"]["translation"], t["transform"]["rotation"], expected[child], child);
        }
        const json odometry = bag().on("/sward/odom/rover")[f]["message"];
        EXPECT_EQ(odometry["child_frame_id"], "rover");
        expectPose(odometry["pose"]["pose"]["position"], odometry["pose"]["pose"]["orientation"], expected["rover"],
                   "odometry");
        // The rover drives its path at 1.2 m/s (examples/rover-lidar.json): the twist's speed, in its own frame.
        const json& v = odometry["twist"]["twist"]["linear"];
        EXPECT_NEAR(std::hypot(v["x"].get<double>(), v["y"].get<double>(), v["z"].get<double>()), 1.2, 0.05);
    }
}

} // namespace

// One render for every check (a ctest process per test would render the dataset again for each).
TEST(SwardExportRos2, FoxglovesReadersDecodeEveryMessageAndItEqualsTheDatasetsFiles) {
    if (!bag().skip.empty()) GTEST_SKIP() << bag().skip;
    ASSERT_FALSE(bag().messages.empty());
    {
        SCOPED_TRACE("expectEveryTopicOncePerFrameAtTheSimulationTime");
        expectEveryTopicOncePerFrameAtTheSimulationTime();
    }
    {
        SCOPED_TRACE("expectImagesAreThePreviewsAndDepthWithTheirIntrinsics");
        expectImagesAreThePreviewsAndDepthWithTheirIntrinsics();
    }
    {
        SCOPED_TRACE("expectLidarCloudIsThePlysPointsWithRingTimeAndLabel");
        expectLidarCloudIsThePlysPointsWithRingTimeAndLabel();
    }
    {
        SCOPED_TRACE("expectScanIsTheScannersRanges");
        expectScanIsTheScannersRanges();
    }
    {
        SCOPED_TRACE("expectTransformsAndOdometryAreThePoses");
        expectTransformsAndOdometryAreThePoses();
    }
}

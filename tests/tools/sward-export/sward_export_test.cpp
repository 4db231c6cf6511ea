// sward-export's layouts read back with each target's own conventions, independently of sward's writers: OpenCV
// for PNG / EXR, a PFM and a PLY reader of this file's own, the text formats parsed field by field. One small
// stereo dataset (2 frames, 160x120) is rendered once and exported to every layout.
#include "gpu_test.h"
#include "pfm_reader.h"

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <sys/wait.h>

using sward::test::readPfm;
using sward::test::tempDir;

namespace {

const std::string kScene = SWARD_TEST_DATA_DIR "/dataset_scene.json";
const char* kFrames[] = {"000000", "000001"};

std::string readFile(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

struct ToolRun {
    int exitCode = -1;
    std::string err;
};

ToolRun run(const std::string& command) {
    const std::string errFile = tempDir("export-log") + "/err.txt";
    const int status = std::system((command + " >/dev/null 2>" + errFile).c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, readFile(errFile)};
}

const std::string& dataset() {
    static const std::string dir = [] {
        const std::string out = tempDir("export-dataset");
        const ToolRun r = run(SWARD_RENDER_EXE " " + kScene + " --out " + out + " --frames 0:2 --validation");
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return out;
    }();
    return dir;
}

std::string exportTo(const std::string& layout, const std::string& extra = "") {
    const std::string out = tempDir("export-" + layout) + "/out";
    const ToolRun r = run(SWARD_EXPORT_EXE " " + dataset() + " --layout " + layout + " --out " + out + " " + extra);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return out;
}

cv::Mat readImage(const std::string& path) {
    cv::Mat image = cv::imread(path, cv::IMREAD_UNCHANGED);
    EXPECT_FALSE(image.empty()) << "cannot read " << path;
    return image;
}

std::map<std::string, std::string> keyValues(const std::string& path, char separator) {
    std::map<std::string, std::string> values;
    std::istringstream lines(readFile(path));
    for (std::string line; std::getline(lines, line);)
        if (auto at = line.find(separator); at != std::string::npos) values[line.substr(0, at)] = line.substr(at + 1);
    return values;
}

std::vector<double> numbers(const std::string& text) {
    std::istringstream in(text);
    std::vector<double> values;
    for (double v; in >> v;) values.push_back(v);
    return values;
}

struct Calib {
    double f = 0, cx = 0, cy = 0, baselineM = 0;
};

Calib middleburyCalib(const std::string& path) {
    auto calib = keyValues(path, '=');
    Calib c;
    EXPECT_EQ(std::sscanf(calib.at("cam0").c_str(), "[%lf 0 %lf; 0 %*f %lf", &c.f, &c.cx, &c.cy), 3);
    c.baselineM = std::stod(calib.at("baseline")) * 1e-3;
    return c;
}

// frames.jsonl's left pose of `frame` (camera-to-world, OpenCV axes), row-major.
std::array<double, 16> leftPose(int frame) {
    std::istringstream lines(readFile(dataset() + "/frames.jsonl"));
    for (std::string line; std::getline(lines, line);) {
        const nlohmann::json record = nlohmann::json::parse(line);
        if (record.at("frame") != frame) continue;
        std::array<double, 16> m{};
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) m[r * 4 + c] = record.at("left_pose")[r][c];
        return m;
    }
    ADD_FAILURE() << "no frame " << frame;
    return {};
}

} // namespace

TEST(SwardExport, MiddleburyPfmIsFocalTimesBaselineOverDepthAndMasksFollowTheRules) {
    const std::string out = exportTo("middlebury");
    for (const char* frame : kFrames) {
        const std::string dir = out + "/" + frame;
        EXPECT_EQ(readFile(dir + "/im0.png"), readFile(dataset() + "/preview/" + frame + ".png"));
        EXPECT_EQ(readFile(dir + "/im1.png"), readFile(dataset() + "/preview_right/" + frame + ".png"));
        EXPECT_EQ(readFile(dir + "/disp1.pfm"), readFile(dataset() + "/disparity_right/" + frame + ".pfm"));
        EXPECT_EQ(readFile(dir + "/mask0nocc.png"), readFile(dataset() + "/occlusion/" + frame + ".png"));
        EXPECT_EQ(readFile(dir + "/mask1nocc.png"), readFile(dataset() + "/occlusion_right/" + frame + ".png"));
        const Calib calib = middleburyCalib(dir + "/calib.txt");
        const cv::Mat depth = readImage(dataset() + "/depth/" + frame + ".exr");
        const cv::Mat disparity = readPfm(dir + "/disp0.pfm");
        const cv::Mat mask = readImage(dir + "/mask0nocc.png");
        ASSERT_EQ(mask.type(), CV_8U);
        int occluded = 0, visible = 0;
        for (int y = 0; y < depth.rows; ++y)
            for (int x = 0; x < depth.cols; ++x) {
                const float z = depth.at<float>(y, x), d = disparity.at<float>(y, x);
                const uint8_t m = mask.at<uint8_t>(y, x);
                if (std::isinf(z)) { // no truth: +inf in the PFM, 0 in the mask
                    ASSERT_TRUE(std::isinf(d));
                    ASSERT_EQ(m, 0);
                    continue;
                }
                ASSERT_NEAR(d, calib.f * calib.baselineM / z, 1e-5 * d) << x << "," << y;
                ASSERT_TRUE(m == 255 || m == 128) << int(m);
                if (x - d < -0.5) {
                    ASSERT_EQ(m, 128) << "match left of the right image at " << x << "," << y;
                }
                (m == 255 ? visible : occluded) += 1;
            }
        EXPECT_GT(visible, 5000);
        EXPECT_GT(occluded, 10); // at least the left border strip
    }
}

TEST(SwardExport, Eth3dHasTheSameTruthUnderItsNames) {
    const std::string out = exportTo("eth3d"), middlebury = exportTo("middlebury");
    for (const char* frame : kFrames) {
        EXPECT_EQ(readFile(out + "/" + frame + "/disp0GT.pfm"), readFile(middlebury + "/" + frame + "/disp0.pfm"));
        for (const char* file : {"im0.png", "im1.png", "calib.txt", "mask0nocc.png"})
            EXPECT_EQ(readFile(out + "/" + frame + "/" + file), readFile(middlebury + "/" + frame + "/" + file)) << file;
    }
}

TEST(SwardExport, KittiPngsHoldTheDisparityWithin1Over256AndNocIsTheVisiblePart) {
    const std::string out = exportTo("kitti"), middlebury = exportTo("middlebury");
    for (const char* frame : kFrames) {
        const std::string name = std::string(frame) + "_10.png";
        const cv::Mat occ = readImage(out + "/training/disp_occ_0/" + name);
        const cv::Mat noc = readImage(out + "/training/disp_noc_0/" + name);
        const cv::Mat d = readPfm(middlebury + "/" + frame + "/disp0.pfm");
        const cv::Mat mask = readImage(middlebury + "/" + frame + "/mask0nocc.png");
        ASSERT_EQ(occ.type(), CV_16U);
        ASSERT_EQ(noc.type(), CV_16U);
        for (int y = 0; y < d.rows; ++y)
            for (int x = 0; x < d.cols; ++x) {
                const float v = d.at<float>(y, x);
                const uint16_t o = occ.at<uint16_t>(y, x), n = noc.at<uint16_t>(y, x);
                if (std::isinf(v)) {
                    ASSERT_EQ(o, 0);
                    ASSERT_EQ(n, 0);
                    continue;
                }
                ASSERT_GT(o, 0); // KITTI: 0 = no value
                ASSERT_LE(std::abs(o / 256.0 - v), 0.5 / 256.0 + 1e-6);
                ASSERT_EQ(n, mask.at<uint8_t>(y, x) == 255 ? o : 0);
            }
        EXPECT_EQ(readFile(out + "/training/image_2/" + name), readFile(dataset() + "/preview/" + frame + ".png"));
        EXPECT_EQ(readFile(out + "/training/image_3/" + name), readFile(dataset() + "/preview_right/" + frame + ".png"));
        auto calib = keyValues(out + "/training/calib_cam_to_cam/" + std::string(frame) + ".txt", ':');
        const std::vector<double> p2 = numbers(calib.at("P_rect_02")), p3 = numbers(calib.at("P_rect_03"));
        ASSERT_EQ(p2.size(), 12u);
        ASSERT_EQ(p3.size(), 12u);
        const Calib c = middleburyCalib(middlebury + "/" + frame + "/calib.txt");
        EXPECT_NEAR(p2[0], c.f, 1e-9);
        EXPECT_NEAR(p2[2], c.cx, 1e-9);
        EXPECT_NEAR(-p3[3] / p3[0], c.baselineM, 1e-9); // the devkit's baseline
    }
}

TEST(SwardExport, KittiRefusesDisparitiesItsPngCannotHoldAndWritesNothing) {
    const std::string folder = tempDir("export-kitti-range"), copy = folder + "/dataset";
    std::filesystem::copy(dataset(), copy, std::filesystem::copy_options::recursive);
    cv::Mat d = readPfm(copy + "/disparity/000001.pfm");
    d.at<float>(60, 80) = 300.0f;
    std::ofstream pfm(copy + "/disparity/000001.pfm", std::ios::binary | std::ios::trunc);
    pfm << "Pf\n" << d.cols << " " << d.rows << "\n-1\n";
    for (int row = d.rows - 1; row >= 0; --row) pfm.write(reinterpret_cast<const char*>(d.ptr<float>(row)), d.cols * 4);
    pfm.close();
    const std::string out = folder + "/out";
    const ToolRun r = run(SWARD_EXPORT_EXE " " + copy + " --layout kitti --out " + out);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("frame 1: disparity 300.000 px at pixel (80, 60) does not fit KITTI's 16-bit PNG"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(folder), {}), 1); // the dataset: no staging left
}

namespace {

struct PlyPoint {
    double x, y, z;
    uint8_t rgb[3], label;
    uint32_t instance;
    float normal[3];
};

// A PLY reader of its own: the header's properties must be exactly these, binary little-endian.
std::vector<PlyPoint> readPly(const std::string& path) {
    const std::string bytes = readFile(path);
    const size_t end = bytes.find("end_header\n");
    EXPECT_NE(end, std::string::npos);
    std::istringstream header(bytes.substr(0, end));
    std::vector<std::string> properties;
    size_t count = 0;
    for (std::string line; std::getline(header, line);) {
        if (line.starts_with("element vertex ")) count = std::stoul(line.substr(15));
        if (line.starts_with("property ")) properties.push_back(line.substr(9));
        if (line.starts_with("format ")) {
            EXPECT_EQ(line, "format binary_little_endian 1.0");
        }
    }
    EXPECT_EQ(properties,
              (std::vector<std::string>{"double x", "double y", "double z", "uchar red", "uchar green", "uchar blue",
                                        "uchar class", "int instance", "float nx", "float ny", "float nz"}));
    const size_t stride = 3 * 8 + 3 + 1 + 4 + 3 * 4;
    EXPECT_EQ(bytes.size() - end - 11, count * stride);
    std::vector<PlyPoint> points(count);
    for (size_t i = 0; i < count; ++i) {
        const char* p = bytes.data() + end + 11 + i * stride;
        std::memcpy(&points[i].x, p, 8);
        std::memcpy(&points[i].y, p + 8, 8);
        std::memcpy(&points[i].z, p + 16, 8);
        std::memcpy(points[i].rgb, p + 24, 3);
        points[i].label = uint8_t(p[27]);
        std::memcpy(&points[i].instance, p + 28, 4);
        std::memcpy(points[i].normal, p + 32, 12);
    }
    return points;
}

} // namespace

TEST(SwardExport, PlyPointsReprojectIntoTheLeftDepthWithTheirClassInstanceAndNormal) {
    for (const char* frameOption : {"world", "camera"}) {
        const std::string out = exportTo("ply", std::string("--point-frame ") + frameOption);
        const Calib calib = middleburyCalib(dataset() + "/calib.txt");
        for (int frame = 0; frame < 2; ++frame) {
            const std::string name = kFrames[frame];
            const std::vector<PlyPoint> points = readPly(out + "/" + name + ".ply");
            const cv::Mat depth = readImage(dataset() + "/depth/" + name + ".exr");
            const cv::Mat semantic = readImage(dataset() + "/semantic/" + name + ".png");
            const cv::Mat instance = readImage(dataset() + "/instance/" + name + ".exr");
            const cv::Mat preview = readImage(dataset() + "/preview/" + name + ".png");
            const cv::Mat normal = readImage(dataset() + "/normal/" + name + ".exr"); // B, G, R = z, y, x
            const std::array<double, 16> m = leftPose(frame);
            const bool world = std::string(frameOption) == "world";
            EXPECT_EQ(points.size(), size_t(cv::countNonZero(depth < std::numeric_limits<float>::infinity())));
            for (const PlyPoint& p : points) {
                double c[3] = {p.x, p.y, p.z}, n[3] = {p.normal[0], p.normal[1], p.normal[2]};
                if (world) { // camera = R^T (p - t)
                    const double d[3] = {p.x - m[3], p.y - m[7], p.z - m[11]};
                    for (int k = 0; k < 3; ++k) c[k] = m[k] * d[0] + m[4 + k] * d[1] + m[8 + k] * d[2];
                    for (int k = 0; k < 3; ++k)
                        n[k] = m[k] * p.normal[0] + m[4 + k] * p.normal[1] + m[8 + k] * p.normal[2];
                }
                const int u = int(std::lround(calib.f * c[0] / c[2] + calib.cx));
                const int v = int(std::lround(calib.f * c[1] / c[2] + calib.cy));
                ASSERT_TRUE(u >= 0 && u < depth.cols && v >= 0 && v < depth.rows) << u << "," << v;
                ASSERT_NEAR(c[2], depth.at<float>(v, u), 1e-4) << u << "," << v;
                ASSERT_EQ(p.label, semantic.at<uint8_t>(v, u));
                ASSERT_EQ(float(p.instance), instance.at<float>(v, u));
                const cv::Vec3b bgr = preview.at<cv::Vec3b>(v, u);
                ASSERT_EQ(p.rgb[0], bgr[2]);
                ASSERT_EQ(p.rgb[2], bgr[0]);
                const cv::Vec3f zyx = normal.at<cv::Vec3f>(v, u);
                for (int k = 0; k < 3; ++k) ASSERT_NEAR(n[k], zyx[2 - k], world ? 1e-6 : 0.0) << u << "," << v;
            }
        }
    }
}

namespace {

// Row-major 3x3 rotation of a unit quaternion (w, x, y, z), COLMAP's Hamilton convention.
std::array<double, 9> quaternionRotation(double w, double x, double y, double z) {
    return {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
            2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
            2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
}

} // namespace

TEST(SwardExport, ColmapTextModelHoldsTheCalibrationAndFramesJsonlPoses) {
    const std::string out = exportTo("colmap");
    const Calib calib = middleburyCalib(dataset() + "/calib.txt");
    std::istringstream cameras(readFile(out + "/sparse/0/cameras.txt"));
    std::string line;
    while (std::getline(cameras, line) && line.starts_with("#")) {}
    std::istringstream camera(line);
    std::string model;
    int id = 0, width = 0, height = 0;
    double fx, fy, cx, cy;
    camera >> id >> model >> width >> height >> fx >> fy >> cx >> cy;
    EXPECT_EQ(id, 1);
    EXPECT_EQ(model, "PINHOLE");
    EXPECT_EQ(width, 160);
    EXPECT_EQ(height, 120);
    EXPECT_NEAR(fx, calib.f, 1e-9);
    EXPECT_NEAR(cx, calib.cx + 0.5, 1e-9); // COLMAP: the top-left pixel's centre is (0.5, 0.5)
    EXPECT_NEAR(cy, calib.cy + 0.5, 1e-9);

    std::istringstream images(readFile(out + "/sparse/0/images.txt"));
    std::vector<std::string> records;
    while (std::getline(images, line))
        if (!line.starts_with("#")) records.push_back(line);
    ASSERT_EQ(records.size(), 8u); // 2 frames x 2 views x (pose line + empty 2D point line)
    for (int frame = 0; frame < 2; ++frame) {
        std::istringstream fields(records[size_t(frame) * 4]); // the left view of the frame
        int imageId = 0, cameraId = 0;
        double q[4], t[3];
        std::string name;
        fields >> imageId >> q[0] >> q[1] >> q[2] >> q[3] >> t[0] >> t[1] >> t[2] >> cameraId >> name;
        EXPECT_EQ(imageId, frame * 2 + 1);
        EXPECT_EQ(cameraId, 1);
        EXPECT_EQ(name, "left/" + std::string(kFrames[frame]) + ".png");
        EXPECT_EQ(readFile(out + "/images/" + name), readFile(dataset() + "/preview/" + kFrames[frame] + ".png"));
        EXPECT_TRUE(records[size_t(frame) * 4 + 1].empty());
        const std::array<double, 9> r = quaternionRotation(q[0], q[1], q[2], q[3]); // world-to-camera
        const std::array<double, 16> pose = leftPose(frame);
        for (int i = 0; i < 3; ++i) {
            double centre = 0; // C = -R^T t
            for (int k = 0; k < 3; ++k) {
                EXPECT_NEAR(r[k * 3 + i], pose[i * 4 + k], 1e-9); // R^T = the pose's rotation
                centre -= r[k * 3 + i] * t[k];
            }
            EXPECT_NEAR(centre, pose[i * 4 + 3], 1e-9);
        }
    }
}

TEST(SwardExport, NerfstudioTransformsAreFramesJsonlPosesInOpenGlAxes) {
    const std::string out = exportTo("nerfstudio");
    const nlohmann::json transforms = nlohmann::json::parse(readFile(out + "/transforms.json"));
    const Calib calib = middleburyCalib(dataset() + "/calib.txt");
    EXPECT_EQ(transforms.at("camera_model"), "OPENCV");
    EXPECT_NEAR(transforms.at("fl_x").get<double>(), calib.f, 1e-9);
    EXPECT_NEAR(transforms.at("cx").get<double>(), calib.cx + 0.5, 1e-9);
    ASSERT_EQ(transforms.at("frames").size(), 4u);
    for (int frame = 0; frame < 2; ++frame) {
        const nlohmann::json& view = transforms.at("frames")[size_t(frame) * 2];
        EXPECT_EQ(view.at("file_path"), "images/left/" + std::string(kFrames[frame]) + ".png");
        const std::array<double, 16> pose = leftPose(frame);
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) {
                const double sign = (c == 1 || c == 2) ? -1.0 : 1.0; // OpenCV y down, z forward -> OpenGL
                EXPECT_EQ(view.at("transform_matrix")[r][c].get<double>(), sign * pose[r * 4 + c]);
            }
    }
}

TEST(SwardExport, LensDistortionGoesIntoColmapAndNerfstudioAndKeepsPixelPairedLayoutsOut) {
    // frames.jsonl as a render with the sensor model's distortion writes it (the images are not looked at).
    const std::string folder = tempDir("export-distorted"), copy = folder + "/dataset";
    std::filesystem::copy(dataset(), copy, std::filesystem::copy_options::recursive);
    std::istringstream lines(readFile(copy + "/frames.jsonl"));
    std::string text;
    for (std::string line; std::getline(lines, line);) {
        nlohmann::json record = nlohmann::json::parse(line);
        record["sensor"] = {{"enabled", true}, {"k1", -0.1}, {"k2", 0.02}, {"k3", 0.0}, {"p1", 0.001}, {"p2", 0.0}};
        text += record.dump() + "\n";
    }
    std::ofstream(copy + "/frames.jsonl", std::ios::trunc) << text;
    ASSERT_EQ(run(SWARD_EXPORT_EXE " " + copy + " --layout colmap --out " + folder + "/colmap").exitCode, 0);
    const std::string cameras = readFile(folder + "/colmap/sparse/0/cameras.txt");
    const std::string line = cameras.substr(cameras.rfind("\n1 ") + 1);
    EXPECT_EQ(line.substr(0, 20), "1 FULL_OPENCV 160 12") << line;
    const std::vector<double> values = numbers(line.substr(line.find("OPENCV") + 6));
    ASSERT_EQ(values.size(), 2u + 12u); // width, height, fx fy cx cy k1 k2 p1 p2 k3 k4 k5 k6
    EXPECT_EQ(values[6], -0.1);
    EXPECT_EQ(values[7], 0.02);
    EXPECT_EQ(values[8], 0.001);
    ASSERT_EQ(run(SWARD_EXPORT_EXE " " + copy + " --layout nerfstudio --out " + folder + "/ns").exitCode, 0);
    const nlohmann::json transforms = nlohmann::json::parse(readFile(folder + "/ns/transforms.json"));
    EXPECT_EQ(transforms.at("k1"), -0.1);
    EXPECT_EQ(transforms.at("p1"), 0.001);
    for (const char* layout : {"middlebury", "kitti", "ply"}) {
        const ToolRun r = run(SWARD_EXPORT_EXE " " + copy + " --layout " + layout + " --out " + folder + "/no");
        EXPECT_EQ(r.exitCode, 1) << layout;
        EXPECT_NE(r.err.find("lens distortion"), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(folder + "/no"));
    }
}

TEST(SwardExport, AFolderThatIsNotADatasetIsOneErrorAndNothingIsWritten) {
    const std::string empty = tempDir("export-not-a-dataset");
    const std::string out = empty + "/out";
    const ToolRun r = run(SWARD_EXPORT_EXE " " + empty + " --layout ply --out " + out);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("dataset.json"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

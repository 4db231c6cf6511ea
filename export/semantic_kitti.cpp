#include "export/semantic_kitti.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/input_file.h"
#include "common/little_endian.h"
#include "common/staged_folder.h"
#include "dataset/naming.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <sstream>

namespace sward {

namespace {

using SensorPoses = std::map<uint32_t, glm::dmat4>; // frame -> world from sensor at the sweep's start

// What frames.jsonl says of the LiDARs, beyond openExportDataset's camera: each frame's time, and each LiDAR's pose
// by name (in name order, which numbers the sequences).
struct LidarLog {
    std::map<uint32_t, double> times;
    std::map<std::string, SensorPoses> poses;
};

LidarLog readLidarLog(const ExportDataset& dataset) {
    const std::string path = dataset.dir + "/" + kFrameLogFile;
    std::istringstream file(readInputFile(path, "frame log"));
    LidarLog log;
    for (std::string line; std::getline(file, line);) try {
            const nlohmann::json record = nlohmann::json::parse(line); // its camera was checked by openExportDataset
            const uint32_t frame = record.at("frame").get<uint32_t>();
            log.times[frame] = record.at("time").get<double>();
            if (!record.contains("range_sensors")) continue;
            for (const nlohmann::json& sensor : record["range_sensors"]) {
                if (sensor.value("type", "") != "lidar") continue;
                glm::dmat4 pose(1.0);
                for (int r = 0; r < 4; ++r)
                    for (int c = 0; c < 4; ++c) pose[c][r] = sensor.at("start_pose").at(r).at(c).get<double>();
                log.poses[sensor.at("name").get<std::string>()][frame] = pose;
            }
        } catch (const nlohmann::json::exception& e) {
            throw Error(path + ": not a sward frame record with range sensors (" + e.what() + ")");
        }
    return log;
}

std::string matrixLine(const glm::dmat4& m) { // KITTI: the top 3x4, row-major
    std::string text;
    char number[32];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) {
            std::snprintf(number, sizeof number, "%s%.12e", text.empty() ? "" : " ", m[c][r]);
            text += number;
        }
    return text + "\n";
}

std::string calibText(const ExportCamera& c, const glm::dmat4& lidarToCamera) {
    auto projection = [&](double tx) { // KITTI's rectified P: [f 0 cx -f*B; 0 f cy 0; 0 0 1 0]
        glm::dmat4 p(0.0);
        p[0][0] = c.fx, p[2][0] = c.cx, p[3][0] = tx;
        p[1][1] = c.fy, p[2][1] = c.cy, p[2][2] = 1.0;
        return p;
    };
    const glm::dmat4 left = projection(0.0), right = projection(-c.fx * c.baseline);
    return "P0: " + matrixLine(left) + "P1: " + matrixLine(right) + "P2: " + matrixLine(left) +
           "P3: " + matrixLine(right) + "Tr: " + matrixLine(lidarToCamera);
}

// The dataset's .label with each point's class in `labels`' ontology; the instance half as it is.
std::string mappedLabels(const std::string& path, LabelOntology labels, size_t points) {
    const std::string bytes = readInputFile(path, "SemanticKITTI label file");
    require(bytes.size() == points * 4, path + ": " + std::to_string(bytes.size()) + " bytes for " +
                                            std::to_string(points) + " points of the .bin (4 per point expected)");
    std::string out;
    out.reserve(bytes.size());
    for (size_t i = 0; i < points; ++i) {
        uint32_t value = 0;
        std::memcpy(&value, bytes.data() + i * 4, 4);
        appendLittleEndian(out, uint32_t((value & 0xffff0000u) | mapLabel(labels, value & 0xffffu)));
    }
    return out;
}

// Tr must be one matrix for the whole sequence: the LiDAR moves with the left camera.
void requireRigid(const glm::dmat4& first, const glm::dmat4& now, const std::string& sensor, uint32_t frame) {
    double worst = 0.0;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r) worst = std::max(worst, std::abs(first[c][r] - now[c][r]));
    require(worst < 1e-5, "LiDAR '" + sensor + "' moves relative to the left camera (frame " + std::to_string(frame) +
                              "): SemanticKITTI's calib.txt holds one LiDAR-to-camera Tr; mount the camera and "
                              "the LiDAR on the same object, or export --layout ply / ros2");
}

void exportSequence(const ExportDataset& dataset, const LidarLog& log, const std::string& dir,
                    const std::string& sensor, LabelOntology labels) {
    const SensorPoses& poses = log.poses.at(sensor);
    makeDirectory(dir + "/velodyne", "output folder");
    makeDirectory(dir + "/labels", "output folder");
    const ExportFrame& first = dataset.frames.front();
    auto poseOf = [&](const ExportFrame& f) {
        const auto found = poses.find(f.frame);
        require(found != poses.end(),
                "frames.jsonl has no pose of LiDAR '" + sensor + "' for frame " + std::to_string(f.frame));
        return found->second;
    };
    const glm::dmat4 lidarToCamera = glm::inverse(first.leftPose) * poseOf(first);
    std::string posesText, timesText;
    for (size_t i = 0; i < dataset.frames.size(); ++i) {
        const ExportFrame& f = dataset.frames[i];
        requireRigid(lidarToCamera, glm::inverse(f.leftPose) * poseOf(f), sensor, f.frame);
        const std::string source = dataset.dir + "/" + kRangeFolder + "/" + sensor + "/" + frameName(f.frame);
        const std::string points = readInputFile(source + ".bin", "KITTI LiDAR scan");
        require(points.size() % 16 == 0,
                source + ".bin: " + std::to_string(points.size()) + " bytes, not a KITTI scan (16 bytes per point)");
        const std::string name = frameName(uint32_t(i));
        writeTextAtomically(dir + "/velodyne/" + name + ".bin", points);
        writeTextAtomically(dir + "/labels/" + name + ".label",
                            mappedLabels(source + ".label", labels, points.size() / 16));
        posesText += matrixLine(glm::inverse(first.leftPose) * f.leftPose);
        char time[32];
        std::snprintf(time, sizeof time, "%.6e\n", log.times.at(f.frame) - log.times.at(first.frame));
        timesText += time;
    }
    writeTextAtomically(dir + "/poses.txt", posesText);
    writeTextAtomically(dir + "/times.txt", timesText);
    writeTextAtomically(dir + "/calib.txt", calibText(dataset.camera, lidarToCamera));
}

void colourLine(std::string& yaml, uint32_t id, const uint8_t* rgb) {
    yaml += "  " + std::to_string(id) + ": [" + std::to_string(rgb[2]) + ", " + std::to_string(rgb[1]) + ", " +
            std::to_string(rgb[0]) + "]\n"; // SemanticKITTI's colour maps are BGR
}

} // namespace

std::string semanticKittiConfig(LabelOntology labels, uint32_t sequences) {
    const std::span<const OntologyClass> classes = ontologyClasses(labels);
    const bool sward = labels == LabelOntology::Sward;
    // Training ids: SemanticKITTI's 20 for sward's classes; an ontology's own classes in order otherwise.
    const std::span<const OntologyClass> training = sward ? semanticKittiTrainingClasses() : classes;
    auto trainingId = [&](uint32_t raw) -> uint32_t {
        if (sward) return semanticKittiTrainingClass(raw);
        for (size_t i = 0; i < classes.size(); ++i)
            if (classes[i].id == raw) return uint32_t(i);
        return 0;
    };
    std::string yaml =
        std::string("# sward-export --layout semantickitti --labels ") + ontologyName(labels) +
        ": the label config of semantic-kitti.yaml's form. labels: the raw ids of the .label files; "
        "learning_map: raw id -> training id (" +
        (sward ? "SemanticKITTI's 20 classes, named in the comments" : "the ontology's classes in order") +
        ").\nname: \"" + (sward ? std::string("sward") : std::string("sward in ") + ontologyName(labels)) +
        "\"\nlabels:\n";
    for (const OntologyClass& c : classes) yaml += "  " + std::to_string(c.id) + ": \"" + c.name + "\"\n";
    yaml += "color_map: # bgr; sward's class colours (classes.json), grey for classes sward never writes\n";
    const uint8_t grey[3] = {128, 128, 128};
    for (const OntologyClass& c : classes) {
        const uint8_t* rgb = grey;
        for (const SemanticClass& s : semanticClasses())
            if (mapLabel(labels, s.id) == c.id) {
                rgb = s.colour;
                break;
            }
        colourLine(yaml, c.id, rgb);
    }
    yaml += "learning_map:\n";
    for (const OntologyClass& c : classes)
        yaml += "  " + std::to_string(c.id) + ": " + std::to_string(trainingId(c.id)) + " # \"" + c.name + "\" -> \"" +
                training[trainingId(c.id)].name + "\"\n";
    yaml += "learning_map_inv: # training id -> a raw id that trains as it (0 where none does)\n";
    for (size_t t = 0; t < training.size(); ++t) {
        uint32_t raw = 0;
        for (const OntologyClass& c : classes)
            if (trainingId(c.id) == t) {
                raw = c.id;
                break;
            }
        yaml += "  " + std::to_string(t) + ": " + std::to_string(raw) + " # \"" + training[t].name + "\"\n";
    }
    yaml += "learning_ignore: # the unlabeled / void class\n";
    for (size_t t = 0; t < training.size(); ++t) yaml += "  " + std::to_string(t) + (t == 0 ? ": True\n" : ": False\n");
    yaml += "split: # sequence numbers\n  train:\n";
    for (uint32_t s = 0; s < sequences; ++s) yaml += "    - " + std::to_string(s) + "\n";
    return yaml + "  valid: []\n  test: []\n";
}

void exportSemanticKitti(const ExportDataset& dataset, const std::string& out, LabelOntology labels) {
    const LidarLog log = readLidarLog(dataset);
    require(!log.poses.empty(), "'" + dataset.dir + "' has no LiDAR (scene range_sensors of type lidar): the " +
                                    "semantickitti layout holds LiDAR scans");
    uint32_t sequence = 0;
    for (const auto& [sensor, poses] : log.poses) {
        char name[32];
        std::snprintf(name, sizeof name, "/sequences/%02u", sequence++);
        makeDirectory(out + "/sequences", "output folder");
        exportSequence(dataset, log, out + name, sensor, labels);
    }
    writeTextAtomically(out + "/semantic-kitti.yaml", semanticKittiConfig(labels, sequence));
}

} // namespace sward

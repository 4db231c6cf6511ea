#include "range/range_files.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/little_endian.h"
#include "dataset/naming.h"
#include "io/image_files.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <map>
#include <utility>

namespace sward {

std::string rangePly(const RangeScan& scan, const std::string& comment) {
    std::string out = "ply\nformat binary_little_endian 1.0\ncomment " + comment + "\nelement vertex " +
                      std::to_string(scan.points.size()) +
                      "\nproperty float x\nproperty float y\nproperty float z\nproperty double wx\nproperty double wy\n"
                      "property double wz\nproperty float intensity\nproperty float time\nproperty ushort ring\n"
                      "property ushort column\nproperty uchar class\nproperty uint instance\n" +
                      (scan.tiles ? "property uint tile\n" : "") + "end_header\n";
    out.reserve(out.size() + scan.points.size() * (scan.tiles ? 57 : 53));
    for (const RangePoint& p : scan.points) {
        appendLittleEndian(out, p.sensor.x, p.sensor.y, p.sensor.z, p.world.x, p.world.y, p.world.z, p.intensity,
                           p.time, uint16_t(p.ring), uint16_t(p.column), uint8_t(p.label >> gpu::kInstanceBits),
                           uint32_t(p.label & ((1u << gpu::kInstanceBits) - 1u)));
        if (scan.tiles) appendLittleEndian(out, p.tile); // a world: instance ids count within a tile
    }
    return out;
}

std::string kittiBin(const RangeScan& scan) {
    std::string out;
    out.reserve(scan.points.size() * 16);
    for (const RangePoint& p : scan.points) appendLittleEndian(out, p.sensor.x, p.sensor.y, p.sensor.z, p.intensity);
    return out;
}

std::string semanticKittiLabel(const RangeScan& scan) {
    // (tile, truth instance id) -> 1.. in ascending order; the tile is 0 but in a world, where ids count within a tile.
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> numbers;
    for (const RangePoint& p : scan.points)
        if (uint32_t id = p.label & ((1u << gpu::kInstanceBits) - 1u)) numbers[{p.tile, id}] = 0;
    require(numbers.size() <= 0xffffu, "a SemanticKITTI .label holds at most 65535 instances per scan (this scan has " +
                                           std::to_string(numbers.size()) + ")");
    uint32_t next = 0;
    for (auto& [id, number] : numbers) number = ++next;
    std::string out;
    out.reserve(scan.points.size() * 4);
    for (const RangePoint& p : scan.points) {
        const uint32_t id = p.label & ((1u << gpu::kInstanceBits) - 1u);
        const uint32_t instance = id ? numbers[{p.tile, id}] & 0xffffu : 0u;
        appendLittleEndian(out, uint32_t((p.label >> gpu::kInstanceBits) | (instance << 16)));
    }
    return out;
}

std::string laserScanJson(const RangeSensorParams& sensor, const RangeScan& scan) {
    nlohmann::json ranges = nlohmann::json::array();
    for (float r : scan.ranges) ranges.push_back(r > 0.0f ? nlohmann::json(r) : nlohmann::json(nullptr));
    const nlohmann::json j = {{"angle_min_deg", sensor.angleMinDegrees},
                              {"angle_increment_deg", sensor.azimuthStepDegrees},
                              {"time_increment_s", scan.columns > 1 ? columnTime(sensor, 1) : 0.0},
                              {"range_min", sensor.minRange},
                              {"range_max", sensor.maxRange},
                              {"ranges", ranges}};
    return j.dump() + "\n";
}

std::vector<float> tofDepth(const RangeSensorParams& sensor, const RangeScan& scan) {
    std::vector<float> depth(size_t(sensor.width) * sensor.height, std::numeric_limits<float>::infinity());
    for (const RangePoint& p : scan.points) depth[size_t(p.ring) * sensor.width + p.column] = p.sensor.x;
    return depth;
}

void writeRangeFiles(DatasetWriter& dataset, const RangeSensorParams& sensor, const RangeScan& scan, uint32_t frame) {
    const std::string comment = "sward range sensor " + sensor.name + " frame " + std::to_string(frame);
    for (const std::string& file : rangeFrameFiles(sensor.name, sensor.type, frame)) {
        const std::string path = dataset.claim(file), extension = std::filesystem::path(file).extension().string();
        if (extension == ".exr")
            writeExrDepth(path, sensor.width, sensor.height, tofDepth(sensor, scan));
        else if (extension == ".ply")
            writeTextAtomically(path, rangePly(scan, comment));
        else if (extension == ".bin")
            writeTextAtomically(path, kittiBin(scan));
        else if (extension == ".label")
            writeTextAtomically(path, semanticKittiLabel(scan));
        else
            writeTextAtomically(path, laserScanJson(sensor, scan));
    }
}

} // namespace sward

// A range sensor's files per frame (docs/dataset-format.md, "Range sensors"), under range/<sensor name>/ of a dataset:
//   LiDAR:   <frame>.ply    binary little-endian PLY: float x, y, z (sensor frame at the point's firing time), double
//                           wx, wy, wz (world), float intensity, float time (s after the sweep's start), ushort ring,
//                           ushort column, uchar class (classes.json), uint instance (the truth images' instance id);
//                           a world of several tiles: uint tile (the plant's tile + 1, as the truth images' tile)
//            <frame>.bin    KITTI Velodyne: float32 x, y, z, intensity per point (sensor frame)
//            <frame>.label  SemanticKITTI: uint32 per point, class in the low 16 bits, in the high 16 bits the point's
//                           instance numbered 1.. in ascending order of its (tile, truth instance id) within the scan
//                           (0: the ground); the PLY keeps the truth id itself
//   Scanner: <frame>.json   {angle_min_deg, angle_increment_deg, time_increment_s, range_min, range_max, ranges: [...]}
//                           (ROS LaserScan's fields; null = no return) and the same points as a PLY
//   ToF:     <frame>.exr    planar depth (along the optical axis, +x), float channels Y and Z; +inf: no return
// Points are in firing order (column, then ring), so every file is a pure function of the scan.
#pragma once

#include "dataset/dataset_writer.h"
#include "range/range_sweep.h"

#include <string>

namespace sward {

std::string rangePly(const RangeScan& scan, const std::string& comment);
std::string kittiBin(const RangeScan& scan);
std::string semanticKittiLabel(const RangeScan& scan);
std::string laserScanJson(const RangeSensorParams& sensor, const RangeScan& scan);
// Planar depth image of a ToF scan (width x height, row-major), +inf where nothing returned.
std::vector<float> tofDepth(const RangeSensorParams& sensor, const RangeScan& scan);

// Writes the files of `scan` (sensor `sensor`, frame `frame`: dataset/naming.h's rangeFrameFiles), each atomically,
// through `dataset` (which removes them again if the run fails).
void writeRangeFiles(DatasetWriter& dataset, const RangeSensorParams& sensor, const RangeScan& scan, uint32_t frame);

} // namespace sward

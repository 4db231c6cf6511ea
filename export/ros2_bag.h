// sward-export --layout ros2: a dataset as a ROS 2 bag (docs/dataset-format.md, "Export"): out/sward_0.mcap, an
// MCAP file with the "ros2" profile (export/mcap_writer.h) of CDR messages (export/ros2_messages.h) whose complete
// definitions are embedded as schemas ("ros2msg"), and the rosbag2 folder's metadata.yaml (version 5, read by
// Humble and later), so `ros2 bag play out` and `ros2 bag info out` take it as a recorded bag.
//
// Per exported frame, stamped with the simulation clock (frames.jsonl `time`, the range sensors' `sweep_start`),
// one chunk: /tf (the cameras, the scene's objects and range sensors in "world"), /sward/left/image_raw and
// /sward/right/image_raw (the previews, rgb8) with their camera_info, /sward/left/depth/image_rect (32FC1, metres,
// +inf for sky) with its camera_info, /sward/range/<name>/points (LiDAR PointCloud2: the PLY's points and
// properties as they are, its `class` named `label`), /sward/range/<name>/scan (scanner LaserScan) and
// /sward/odom/left_camera and /sward/odom/<object> (nav_msgs/Odometry). The same dataset gives the same bytes.
#pragma once

#include "export/export_source.h"

#include <string>

namespace sward {

inline constexpr const char* kRos2BagFile = "sward_0.mcap";
inline constexpr const char* kRos2MetadataFile = "metadata.yaml";

// Writes the bag of every frame of `dataset` into the folder `out`. Throws one sward::Error naming the file for a
// frame record, LiDAR PLY or scan it cannot carry, or for two bodies that would share a TF frame name.
void exportRos2Bag(const ExportDataset& dataset, const std::string& out);

} // namespace sward

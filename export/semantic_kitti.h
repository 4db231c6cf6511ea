// The SemanticKITTI layout (docs/dataset-format.md, "Export"): each LiDAR of the dataset as one sequence that the
// semantic-kitti-api and the models trained on SemanticKITTI read as they are:
//   sequences/NN/velodyne/NNNNNN.bin   the dataset's KITTI .bin (float32 x, y, z, intensity; sensor frame)
//   sequences/NN/labels/NNNNNN.label   uint32 per point: class (in --labels' ontology) in the low 16 bits, the
//                                      dataset's per-scan instance number in the high 16 bits
//   sequences/NN/poses.txt             the left camera's pose per scan in the first scan's camera frame, 3x4
//                                      row-major (KITTI odometry)
//   sequences/NN/calib.txt             P0..P3 (left, right, left, right: sward's rig is one stereo pair) and Tr
//                                      (LiDAR to left camera, constant: the LiDAR must ride with the camera)
//   sequences/NN/times.txt             seconds since the first scan
//   semantic-kitti.yaml                the label config: labels, color_map (BGR), learning_map,
//                                      learning_map_inv, learning_ignore, split
// Scans are numbered from 000000 in frame order; NN counts the dataset's LiDARs in frames.jsonl's order.
#pragma once

#include "export/export_source.h"
#include "export/label_maps.h"

#include <string>

namespace sward {

void exportSemanticKitti(const ExportDataset& dataset, const std::string& out, LabelOntology labels);

// semantic-kitti.yaml for `labels` (exposed for tests). sward: its classes as the raw labels and a learning_map
// onto SemanticKITTI's 20 training classes; rellis / rugd / goose: their classes, learning_map onto their own
// consecutive training ids (RELLIS-3D's as rellis.yaml numbers them).
std::string semanticKittiConfig(LabelOntology labels, uint32_t sequences);

} // namespace sward

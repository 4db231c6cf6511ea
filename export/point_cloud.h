// Coloured, labelled point clouds: one binary little-endian PLY per frame, one point per left pixel with ground
// truth (sky has none), in row-major pixel order. Properties: double x, y, z (metres; world frame: right-handed,
// z up; camera frame: OpenCV axes), uchar red, green, blue (the tonemapped left preview), uchar class (semantic
// id, classes.json, or its class in RELLIS-3D, RUGD or GOOSE: export/label_maps.h), int instance (int32: Open3D
// drops uint properties) and, when the dataset has normal/ files, float nx, ny, nz (the surface normal, unit,
// facing the camera, in the points' frame). Open3D (every property, o3d.t.io), CloudCompare and MeshLab read it as
// it is.
#pragma once

#include "export/export_source.h"
#include "export/label_maps.h"

#include <string>

namespace sward {

enum class PointFrame { World, Camera };

// Writes out/NNNNNN.ply for every frame of `dataset`, the class property in `labels`' ontology.
void exportPointClouds(const ExportDataset& dataset, const std::string& out, PointFrame frame,
                       LabelOntology labels = LabelOntology::Sward);

// The PLY bytes of one frame (exposed for tests): points from `truth` and the left camera, moved by `pose`
// (camera-to-world; identity for the camera frame), classes in `labels`' ontology.
std::string pointCloudPly(const FrameTruth& truth, const ExportCamera& camera, const glm::dmat4& pose,
                          const std::string& comment, LabelOntology labels = LabelOntology::Sward);

} // namespace sward

// Camera poses for reconstruction tools, from frames.jsonl's calibration: a COLMAP text model and a nerfstudio
// transforms.json. Both name the images they describe: the tonemapped previews, copied to images/left/NNNNNN.png
// and images/right/NNNNNN.png. Both tools put pixel centres at +0.5 (the top-left pixel's centre is (0.5, 0.5)),
// so their cx, cy are calib.txt's + 0.5.
#pragma once

#include "export/export_source.h"

#include <string>

namespace sward {

// sparse/0/cameras.txt (one PINHOLE camera: the rig is rectified; FULL_OPENCV with the sensor model's lens
// distortion), images.txt (world-to-camera quaternion and
// translation per view, left then right per frame, no 2D points), points3D.txt (empty), the images, and
// database.db: COLMAP's database with the same camera and image ids (export/colmap_database.h).
void exportColmap(const ExportDataset& dataset, const std::string& out);

// transforms.json (camera_model OPENCV with the sensor model's k1, k2, k3, p1, p2, zero without; transform_matrix camera-to-world in OpenGL axes: x right,
// y up, z back) and the images.
void exportNerfstudio(const ExportDataset& dataset, const std::string& out);

// The unit quaternion of a rotation matrix, as COLMAP writes it: (qw, qx, qy, qz) in the vector's x, y, z, w, with
// qw >= 0 (exposed for tests).
glm::dvec4 rotationQuaternion(const glm::dmat3& r);

} // namespace sward

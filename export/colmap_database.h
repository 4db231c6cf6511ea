// COLMAP's database.db for an exported model (export/camera_models.h): the cameras and images tables with the very
// ids of sparse/0's cameras.txt and images.txt, so that `colmap feature_extractor` (which keeps an image that is
// already in the database, with its id and camera) and `point_triangulator` on the model run unchanged; COLMAP
// itself numbers images in the order its threads finish them, which need not be the model's.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace sward {

struct ColmapCameraRow {
    uint32_t id = 1;
    int model = 1; // COLMAP's model id: 1 PINHOLE, 6 FULL_OPENCV
    uint32_t width = 0, height = 0;
    std::vector<double> params; // in the model's order, as cameras.txt lists them
};

struct ColmapImageRow {
    uint32_t id = 0;
    std::string name; // relative to the images folder, as images.txt names it
    uint32_t cameraId = 1;
    glm::dvec4 rotation{1, 0, 0, 0}; // world-to-camera quaternion (qw, qx, qy, qz) as x, y, z, w, the prior
    glm::dvec3 translation{0.0};     // world-to-camera translation, the prior
};

// The bytes of a SQLite database with COLMAP 3.8's schema (every table it creates) holding `cameras` and
// `images`; the same rows give the same bytes with one SQLite library. Throws sward::Error when SQLite fails.
std::vector<char> colmapDatabaseBytes(const std::vector<ColmapCameraRow>& cameras,
                                      const std::vector<ColmapImageRow>& images);

} // namespace sward

#include "export/point_cloud.h"

#include "common/atomic_file.h"
#include "common/little_endian.h"
#include "dataset/naming.h"

#include <cmath>

namespace sward {

std::string pointCloudPly(const FrameTruth& truth, const ExportCamera& camera, const glm::dmat4& pose,
                          const std::string& comment, LabelOntology labels) {
    std::string body;
    size_t count = 0;
    const bool normals = !truth.normal.empty();
    for (uint32_t y = 0; y < truth.height; ++y)
        for (uint32_t x = 0; x < truth.width; ++x) {
            const size_t i = size_t(y) * truth.width + x;
            const double z = truth.depth[i];
            if (!std::isfinite(z) || z <= 0.0) continue; // sky: no surface
            // OpenCV pixel centres: pixel (x, y) looks through (x, y) of the intrinsics' image plane.
            const glm::dvec4 p =
                pose * glm::dvec4((x - camera.cx) * z / camera.fx, (y - camera.cy) * z / camera.fy, z, 1.0);
            appendLittleEndian(body, p.x);
            appendLittleEndian(body, p.y);
            appendLittleEndian(body, p.z);
            body.append(reinterpret_cast<const char*>(&truth.rgb[i * 3]), 3);
            appendLittleEndian(body, uint8_t(mapLabel(labels, truth.semantic[i]))); // every ontology's ids are < 256
            // int32, not uint32: Open3D (0.16) drops a uint property; ids are below 2^24 (export_source.cpp).
            appendLittleEndian(body, int32_t(truth.instance[i]));
            if (normals) {
                const glm::dvec3 n = glm::dmat3(pose) *
                                     glm::dvec3(truth.normal[3 * i], truth.normal[3 * i + 1], truth.normal[3 * i + 2]);
                for (int c = 0; c < 3; ++c) appendLittleEndian(body, float(n[c]));
            }
            ++count;
        }
    const std::string header =
        "ply\nformat binary_little_endian 1.0\ncomment " + comment + "\nelement vertex " + std::to_string(count) +
        "\nproperty double x\nproperty double y\nproperty double z\n"
        "property uchar red\nproperty uchar green\nproperty uchar blue\n"
        "property uchar class\nproperty int instance\n" +
        (normals ? "property float nx\nproperty float ny\nproperty float nz\n" : "") + "end_header\n";
    return header + body;
}

void exportPointClouds(const ExportDataset& dataset, const std::string& out, PointFrame frame, LabelOntology labels) {
    requireUndistorted(dataset, "ply"); // a point's colour is its pixel's
    for (const ExportFrame& f : dataset.frames) {
        const FrameTruth truth = readFrameTruth(dataset, f.frame);
        const std::string comment = "sward frame " + frameName(f.frame) +
                                    (frame == PointFrame::World ? ", world frame (right-handed, z up, metres)"
                                                                : ", left camera frame (OpenCV axes, metres)");
        const glm::dmat4 pose = frame == PointFrame::World ? f.leftPose : glm::dmat4(1.0);
        writeTextAtomically(out + "/" + frameName(f.frame) + ".ply",
                            pointCloudPly(truth, dataset.camera, pose, comment, labels));
    }
}

} // namespace sward

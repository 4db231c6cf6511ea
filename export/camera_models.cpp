#include "export/camera_models.h"

#include "common/atomic_file.h"
#include "common/staged_folder.h"
#include "dataset/naming.h"
#include "export/colmap_database.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>

namespace sward {

namespace {

// Shortest round-trip decimal of a double: the text files lose nothing.
std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", v);
    return text;
}

struct View {
    std::string name; // relative to the images folder
    glm::dmat4 pose;  // camera-to-world, OpenCV axes
};

// Left then right per frame; copies their previews into out/images/{left,right}/.
std::vector<View> copyViews(const ExportDataset& dataset, const std::string& imagesDir) {
    std::vector<View> views;
    makeDirectory(imagesDir + "/left", "output folder");
    if (dataset.stereo) makeDirectory(imagesDir + "/right", "output folder");
    for (const ExportFrame& f : dataset.frames) {
        for (bool right : {false, true}) {
            if (right && !dataset.stereo) continue;
            const std::string name = std::string(right ? "right/" : "left/") + frameName(f.frame) + ".png";
            const std::vector<char> bytes =
                readFrameFileBytes(dataset, right ? kPreviewRightFolder : kPreviewFolder, f.frame, ".png");
            writeBytesAtomically(imagesDir + "/" + name, bytes.data(), bytes.size());
            views.push_back({name, right ? f.rightPose : f.leftPose});
        }
    }
    return views;
}

} // namespace

glm::dvec4 rotationQuaternion(const glm::dmat3& m) {
    auto r = [&](int row, int col) { return m[col][row]; };
    const double trace = r(0, 0) + r(1, 1) + r(2, 2);
    glm::dvec4 q; // (w, x, y, z)
    if (trace > 0.0) {
        const double s = 2.0 * std::sqrt(1.0 + trace);
        q = {0.25 * s, (r(2, 1) - r(1, 2)) / s, (r(0, 2) - r(2, 0)) / s, (r(1, 0) - r(0, 1)) / s};
    } else if (r(0, 0) > r(1, 1) && r(0, 0) > r(2, 2)) {
        const double s = 2.0 * std::sqrt(1.0 + r(0, 0) - r(1, 1) - r(2, 2));
        q = {(r(2, 1) - r(1, 2)) / s, 0.25 * s, (r(0, 1) + r(1, 0)) / s, (r(0, 2) + r(2, 0)) / s};
    } else if (r(1, 1) > r(2, 2)) {
        const double s = 2.0 * std::sqrt(1.0 + r(1, 1) - r(0, 0) - r(2, 2));
        q = {(r(0, 2) - r(2, 0)) / s, (r(0, 1) + r(1, 0)) / s, 0.25 * s, (r(1, 2) + r(2, 1)) / s};
    } else {
        const double s = 2.0 * std::sqrt(1.0 + r(2, 2) - r(0, 0) - r(1, 1));
        q = {(r(1, 0) - r(0, 1)) / s, (r(0, 2) + r(2, 0)) / s, (r(1, 2) + r(2, 1)) / s, 0.25 * s};
    }
    q /= std::sqrt(glm::dot(q, q));
    return q.x < 0.0 ? -q : q;
}

void exportColmap(const ExportDataset& dataset, const std::string& out) {
    const std::vector<View> views = copyViews(dataset, out + "/images");
    const ExportCamera& c = dataset.camera;
    const std::string model = out + "/sparse/0";
    makeDirectory(model, "output folder");
    // The sensor model's lens distortion is OpenCV's: COLMAP's FULL_OPENCV (k4..k6 = 0) holds it exactly.
    ColmapCameraRow camera{.model = c.distorted() ? 6 : 1,
                           .width = c.width,
                           .height = c.height,
                           .params = {c.fx, c.fy, c.cx + 0.5, c.cy + 0.5}};
    if (c.distorted())
        camera.params.insert(camera.params.end(), {c.distortion[0], c.distortion[1], c.distortion[2], c.distortion[3],
                                                   c.distortion[4], 0.0, 0.0, 0.0});
    std::string params;
    for (double p : camera.params) params += " " + number(p);
    writeTextAtomically(model + "/cameras.txt",
                        "# Camera list with one line of data per camera:\n"
                        "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n# Number of cameras: 1\n1 " +
                            std::string(c.distorted() ? "FULL_OPENCV " : "PINHOLE ") + std::to_string(c.width) + " " +
                            std::to_string(c.height) + params + "\n");
    std::string images = "# Image list with two lines of data per image:\n"
                         "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
                         "#   POINTS2D[] as (X, Y, POINT3D_ID)\n# Number of images: " +
                         std::to_string(views.size()) + ", mean observations per image: 0\n";
    std::vector<ColmapImageRow> rows;
    for (size_t i = 0; i < views.size(); ++i) {
        // COLMAP stores world-to-camera: R = R_wc^T, t = -R * C.
        const glm::dmat3 rotation = glm::transpose(glm::dmat3(views[i].pose));
        const glm::dvec3 t = -(rotation * glm::dvec3(views[i].pose[3]));
        const glm::dvec4 q = rotationQuaternion(rotation);
        rows.push_back({.id = uint32_t(i + 1), .name = views[i].name, .rotation = q, .translation = t});
        images += std::to_string(i + 1) + " " + number(q.x) + " " + number(q.y) + " " + number(q.z) + " " +
                  number(q.w) + " " + number(t.x) + " " + number(t.y) + " " + number(t.z) + " 1 " + views[i].name +
                  "\n\n";
    }
    writeTextAtomically(model + "/images.txt", images);
    writeTextAtomically(model + "/points3D.txt",
                        "# 3D point list with one line of data per point:\n"
                        "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n"
                        "# Number of points: 0, mean track length: 0\n");
    // The same ids in COLMAP's database: feature_extractor keeps them, so point_triangulator finds the model's
    // images under the database's ids.
    const std::vector<char> database = colmapDatabaseBytes({camera}, rows);
    writeBytesAtomically(out + "/database.db", database.data(), database.size());
}

void exportNerfstudio(const ExportDataset& dataset, const std::string& out) {
    const std::vector<View> views = copyViews(dataset, out + "/images");
    const ExportCamera& c = dataset.camera;
    // OpenCV camera axes (x right, y down, z forward) -> OpenGL (x right, y up, z back): negate y and z columns.
    const glm::dmat4 flip(glm::dvec4(1, 0, 0, 0), glm::dvec4(0, -1, 0, 0), glm::dvec4(0, 0, -1, 0),
                          glm::dvec4(0, 0, 0, 1));
    nlohmann::json frames = nlohmann::json::array();
    for (const View& view : views) {
        const glm::dmat4 m = view.pose * flip;
        nlohmann::json rows = nlohmann::json::array();
        for (int r = 0; r < 4; ++r) rows.push_back({m[0][r], m[1][r], m[2][r], m[3][r]});
        frames.push_back({{"file_path", "images/" + view.name}, {"transform_matrix", rows}});
    }
    const nlohmann::json transforms = {
        {"camera_model", "OPENCV"}, {"fl_x", c.fx},          {"fl_y", c.fy},          {"cx", c.cx + 0.5},
        {"cy", c.cy + 0.5},         {"w", c.width},          {"h", c.height},         {"k1", c.distortion[0]},
        {"k2", c.distortion[1]},    {"p1", c.distortion[2]}, {"p2", c.distortion[3]}, {"k3", c.distortion[4]},
        {"frames", frames}};
    writeTextAtomically(out + "/transforms.json", transforms.dump(2) + "\n");
}

} // namespace sward

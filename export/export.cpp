#include "export/export.h"

#include "common/error.h"
#include "common/staged_folder.h"
#include "export/camera_models.h"
#include "export/ros2_bag.h"
#include "export/semantic_kitti.h"
#include "export/stereo_layouts.h"

namespace sward {

namespace {

struct LayoutName {
    const char* name;
    ExportLayout layout;
};
constexpr LayoutName kLayouts[] = {{"middlebury", ExportLayout::Middlebury}, {"eth3d", ExportLayout::Eth3d},
                                   {"kitti", ExportLayout::Kitti},           {"ply", ExportLayout::Ply},
                                   {"colmap", ExportLayout::Colmap},         {"nerfstudio", ExportLayout::Nerfstudio},
                                   {"ros2", ExportLayout::Ros2},             {"semantickitti", ExportLayout::SemanticKitti}};

} // namespace

ExportLayout parseExportLayout(const std::string& text, const std::string& what) {
    std::string names;
    for (const LayoutName& l : kLayouts) {
        if (text == l.name) return l.layout;
        names += (names.empty() ? "" : ", ") + std::string(l.name);
    }
    throw Error(what + " '" + text + "' is not a layout (expected one of " + names + ")");
}

PointFrame parsePointFrame(const std::string& text, const std::string& what) {
    if (text == "world") return PointFrame::World;
    if (text == "camera") return PointFrame::Camera;
    throw Error(what + " '" + text + "' is not a point frame (expected world or camera)");
}

uint32_t runExport(const ExportOptions& options) {
    // Everything is read and checked before the output folder is touched, as far as it can be: the dataset's
    // description and frame list here, each frame's files as it is converted into the staging folder.
    require(options.labels == LabelOntology::Sward || options.layout == ExportLayout::Ply ||
                options.layout == ExportLayout::SemanticKitti,
            std::string("--labels ") + ontologyName(options.labels) +
                " applies to the ply and semantickitti layouts (the others carry no class ids)");
    const ExportDataset dataset = openExportDataset(options.datasetDir, options.frames);
    StagedFolder staged(options.outDir, "output folder");
    switch (options.layout) {
    case ExportLayout::Middlebury: exportTwoView(dataset, staged.path(), false); break;
    case ExportLayout::Eth3d: exportTwoView(dataset, staged.path(), true); break;
    case ExportLayout::Kitti: exportKitti(dataset, staged.path()); break;
    case ExportLayout::Ply: exportPointClouds(dataset, staged.path(), options.pointFrame, options.labels); break;
    case ExportLayout::Colmap: exportColmap(dataset, staged.path()); break;
    case ExportLayout::Nerfstudio: exportNerfstudio(dataset, staged.path()); break;
    case ExportLayout::Ros2: exportRos2Bag(dataset, staged.path()); break;
    case ExportLayout::SemanticKitti: exportSemanticKitti(dataset, staged.path(), options.labels); break;
    }
    staged.commit();
    return uint32_t(dataset.frames.size());
}

} // namespace sward

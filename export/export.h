// sward-export: a sward dataset rewritten in the layouts other tools read (docs/dataset-format.md, "Export").
// The output folder appears whole or not at all (common/staged_folder.h); files already in it that the export
// does not write are left alone.
#pragma once

#include "export/label_maps.h"
#include "export/point_cloud.h"

#include <cstdint>
#include <optional>
#include <string>
#include <utility>

namespace sward {

enum class ExportLayout { Middlebury, Eth3d, Kitti, Ply, Colmap, Nerfstudio, Ros2, SemanticKitti };

// "middlebury", "eth3d", "kitti", "ply", "colmap", "nerfstudio", "ros2", "semantickitti"; throws a clear error
// naming `what` (the flag) and the choices.
ExportLayout parseExportLayout(const std::string& text, const std::string& what);
// "world" or "camera".
PointFrame parsePointFrame(const std::string& text, const std::string& what);

struct ExportOptions {
    std::string datasetDir;
    std::string outDir;
    ExportLayout layout = ExportLayout::Middlebury;
    std::optional<std::pair<uint32_t, uint32_t>> frames; // [first, end); all rendered frames when empty
    PointFrame pointFrame = PointFrame::World;
    // The class ids of the ply and semantickitti layouts (export/label_maps.h); only those take another than sward.
    LabelOntology labels = LabelOntology::Sward;
};

// Runs the export; returns the number of frames written. Throws one sward::Error on bad input.
uint32_t runExport(const ExportOptions& options);

} // namespace sward

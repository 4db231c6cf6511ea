// The two-view stereo benchmark layouts (docs/dataset-format.md, "Export"): the dataset's files copied byte for
// byte where the target takes them (previews as im0 / im1, the PFM disparities, calib.txt, the occlusion masks
// of dataset/occlusion.h). Files are written under `out` (sward-export's staging folder).
#pragma once

#include "export/export_source.h"

#include <string>

namespace sward {

// Middlebury 2014 or ETH3D two-view: one folder per frame, NNNNNN/ with im0.png, im1.png, calib.txt, the left
// disparity (Middlebury disp0.pfm, ETH3D disp0GT.pfm) and mask0nocc.png (255 visible in both views, 128
// occluded, 0 no truth); Middlebury also disp1.pfm and mask1nocc.png of the right view.
void exportTwoView(const ExportDataset& dataset, const std::string& out, bool eth3d);

// KITTI 2015 stereo: training/image_2, image_3, disp_occ_0, disp_noc_0 (NNNNNN_10.png) and
// training/calib_cam_to_cam/NNNNNN.txt. Refuses a frame whose disparities the 16-bit PNG cannot hold
// (round(d * 256) outside 1..65535).
void exportKitti(const ExportDataset& dataset, const std::string& out);

} // namespace sward

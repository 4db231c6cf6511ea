#include "export/stereo_layouts.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/staged_folder.h"
#include "dataset/naming.h"
#include "io/disparity_files.h"

#include <cmath>
#include <filesystem>
#include <cstdio>

namespace sward {

namespace {

void copyFrameFile(const ExportDataset& dataset, const char* folder, uint32_t frame, const char* extension,
                   const std::string& target) {
    const std::vector<char> bytes = readFrameFileBytes(dataset, folder, frame, extension);
    writeBytesAtomically(target, bytes.data(), bytes.size());
}

void requireStereo(const ExportDataset& dataset, const char* layout) {
    requireUndistorted(dataset, layout);
    require(dataset.stereo, "'" + dataset.dir + "' is a mono dataset; the " + layout +
                                " layout needs a stereo rig (camera.baseline > 0)");
    std::error_code ec;
    require(std::filesystem::is_directory(dataset.dir + "/" + kOcclusionFolder, ec),
            "'" + dataset.dir + "' has no " + kOcclusionFolder + "/ masks (rendered by an older sward); render it "
                "again to export the " + layout + " layout");
}

// KITTI stores round(d * 256) in 16 bits with 0 as "no value": a disparity outside that range cannot be exported.
void requireKittiRange(const ExportDataset& dataset, uint32_t frame, const std::vector<float>& disparity) {
    const uint32_t w = dataset.camera.width;
    for (size_t i = 0; i < disparity.size(); ++i) {
        if (!isValidDisparity(disparity[i])) continue;
        const double value = std::round(double(disparity[i]) * 256.0);
        if (value >= 1.0 && value <= 65535.0) continue;
        char text[320];
        std::snprintf(text, sizeof text,
                      "frame %u: disparity %.3f px at pixel (%zu, %zu) does not fit KITTI's 16-bit PNG "
                      "(1/256 .. 255.996 px); render with a larger camera.min_depth or baseline, or export "
                      "--layout middlebury (PFM floats)",
                      frame, double(disparity[i]), i % w, i / w);
        throw Error(text);
    }
}

// calib_cam_to_cam in KITTI's fields: cameras 02 (left) and 03 (right) of a rectified rig; P_rect_03 carries
// -f * B in its fourth column, from which the devkit takes the baseline.
std::string kittiCalibText(const ExportCamera& c) {
    auto line = [](const std::string& key, std::initializer_list<double> values) {
        std::string text = key + ":";
        char number[32];
        for (double v : values) {
            std::snprintf(number, sizeof number, " %.16e", v);
            text += number;
        }
        return text + "\n";
    };
    std::string text;
    for (int cam : {2, 3}) {
        const std::string id = cam == 2 ? "02" : "03";
        const double tx = cam == 2 ? 0.0 : -c.baseline;
        text += line("S_" + id, {double(c.width), double(c.height)});
        text += line("K_" + id, {c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1});
        text += line("D_" + id, {0, 0, 0, 0, 0});
        text += line("R_" + id, {1, 0, 0, 0, 1, 0, 0, 0, 1});
        text += line("T_" + id, {tx, 0, 0});
        text += line("S_rect_" + id, {double(c.width), double(c.height)});
        text += line("R_rect_" + id, {1, 0, 0, 0, 1, 0, 0, 0, 1});
        text += line("P_rect_" + id, {c.fx, 0, c.cx, c.fx * tx, 0, c.fy, c.cy, 0, 0, 0, 1, 0});
    }
    return text;
}

} // namespace

void exportTwoView(const ExportDataset& dataset, const std::string& out, bool eth3d) {
    requireStereo(dataset, eth3d ? "eth3d" : "middlebury");
    const std::vector<char> calib = readCalibBytes(dataset);
    for (const ExportFrame& f : dataset.frames) {
        const std::string dir = out + "/" + frameName(f.frame);
        makeDirectory(dir, "output folder");
        copyFrameFile(dataset, kPreviewFolder, f.frame, ".png", dir + "/im0.png");
        copyFrameFile(dataset, kPreviewRightFolder, f.frame, ".png", dir + "/im1.png");
        writeBytesAtomically(dir + "/calib.txt", calib.data(), calib.size());
        copyFrameFile(dataset, kDisparityFolder, f.frame, ".pfm", dir + (eth3d ? "/disp0GT.pfm" : "/disp0.pfm"));
        if (!eth3d) copyFrameFile(dataset, kDisparityRightFolder, f.frame, ".pfm", dir + "/disp1.pfm");
        // sward's occlusion masks use Middlebury's values (255 / 128 / 0).
        copyFrameFile(dataset, kOcclusionFolder, f.frame, ".png", dir + "/mask0nocc.png");
        if (!eth3d) copyFrameFile(dataset, kOcclusionRightFolder, f.frame, ".png", dir + "/mask1nocc.png");
    }
}

void exportKitti(const ExportDataset& dataset, const std::string& out) {
    requireStereo(dataset, "kitti");
    const uint32_t w = dataset.camera.width, h = dataset.camera.height;
    const std::string root = out + "/training";
    for (const char* folder : {"image_2", "image_3", "disp_occ_0", "disp_noc_0", "calib_cam_to_cam"})
        makeDirectory(root + "/" + folder, "output folder");
    for (const ExportFrame& f : dataset.frames) {
        std::vector<float> disparity = readFrameDisparity(dataset, f.frame);
        requireKittiRange(dataset, f.frame, disparity);
        const std::string name = frameName(f.frame) + "_10.png"; // KITTI: frame 10 is the reference of a pair
        copyFrameFile(dataset, kPreviewFolder, f.frame, ".png", root + "/image_2/" + name);
        copyFrameFile(dataset, kPreviewRightFolder, f.frame, ".png", root + "/image_3/" + name);
        writeKittiPng(root + "/disp_occ_0/" + name, w, h, disparity);
        const std::vector<uint8_t> mask = readOcclusionMask(dataset, f.frame);
        for (size_t i = 0; i < disparity.size(); ++i)
            if (mask[i] != 255) disparity[i] = 0.0f; // disp_noc_0: pixels visible in both views only
        writeKittiPng(root + "/disp_noc_0/" + name, w, h, disparity);
        writeTextAtomically(root + "/calib_cam_to_cam/" + frameName(f.frame) + ".txt", kittiCalibText(dataset.camera));
    }
}

} // namespace sward

// The regions `sward-eval look` measures (docs/evaluation.md, "Realism statistics"): those of a sward frame from its
// semantic image, and those of a real photograph from the reference folder's optional regions.json. Reference
// files are read through the one input door (common/input_file.h), and no path may leave the reference folder.
#pragma once

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace sward {

inline constexpr double kLookFarBandFraction = 0.08; // the far band: this share of the frame height
inline constexpr const char* kLookRegionsFile = "regions.json";

// A named region: `mask` is CV_8U of the image's size, 255 inside.
struct LookRegion {
    std::string name;
    cv::Mat mask;
};

// The regions of a sward frame, always these four in this order (a region may be empty):
// "all" every non-sky pixel; "vegetation" the vegetation categories, felled, cut and turf; "soil" ground and
// track; "turf" the turf class alone (issue 46's smooth-turf test); "far" the pixels neither sky nor object in the kLookFarBandFraction of the frame height (rounded up)
// from the topmost row holding such a pixel.
std::vector<LookRegion> swardRegions(const cv::Mat& semantic);
inline constexpr const char* kSwardRegionNames[] = {"all", "vegetation", "soil", "turf", "far"};

// One real photograph of the reference folder and what regions.json says of it.
struct ReferenceImage {
    std::string file; // the file name inside the folder
    cv::Mat bgr;      // CV_8UC3
    std::vector<LookRegion> regions;
};

// Every *.png, *.jpg and *.jpeg (any case) directly in `dir`, by file name, decoded to 8-bit BGR, with its regions:
// regions.json's entry for the file name ({"soil": [[x, y, w, h], ...], "vegetation": "mask.png"}: crop
// rectangles, clipped to the image, or a mask PNG in `dir` whose non-zero pixels are the region), or one region
// "all" (the whole image) without an entry. Throws sward::Error naming the file: a missing folder, no image, an
// undecodable image, a name leaving the folder, a malformed regions.json or a mask of another size.
std::vector<ReferenceImage> readReferenceImages(const std::string& dir);

} // namespace sward

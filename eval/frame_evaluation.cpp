#include "eval/frame_evaluation.h"

#include "common/error.h"
#include "common/stopwatch.h"
#include "dataset/naming.h"
#include "eval/dataset_reader.h"
#include "eval/pictures.h"

#include <algorithm>

namespace sward {

namespace {

void requireSize(const std::string& what, uint32_t width, uint32_t height, const DisparityMap& truth) {
    require(width == truth.width && height == truth.height,
            what + " " + std::to_string(width) + "x" + std::to_string(height) + ", the ground truth " +
                std::to_string(truth.width) + "x" + std::to_string(truth.height));
}

// SGBM on the frame's previews (timed into work.matchSeconds), or the estimate read from disparitiesDir.
std::vector<float> estimateDisparity(const DatasetSetup& setup, const DisparityMap& truth, FrameWork& work) {
    const uint32_t w = truth.width, h = truth.height, frame = work.frame;
    if (!setup.sgbm) return readEstimate(setup.disparitiesDir, frame, w, h);
    const bool gray = setup.sgbm->options.gray;
    cv::Mat left = readPreview(setup.dir, kPreviewFolder, frame, gray);
    cv::Mat right = readPreview(setup.dir, kPreviewRightFolder, frame, gray);
    for (const cv::Mat* view : {&left, &right})
        requireSize(setup.dir + ": preview images of frame " + frameName(frame) + " are", uint32_t(view->cols),
                    uint32_t(view->rows), truth);
    const Stopwatch matching;
    std::vector<float> estimate = runSgbm(*setup.sgbm, w, h, {left.data, left.total() * left.elemSize()},
                                          {right.data, right.total() * right.elemSize()});
    work.matchSeconds = matching.seconds();
    if (setup.options->saveDisparities)
        writePfm(setup.pictureDir + "/disparity/" + frameName(frame) + ".pfm", w, h, estimate);
    return estimate;
}

// Adds every pixel with ground truth to the total, its class group and its distance band.
void accumulateErrors(const DatasetSetup& setup, const DisparityMap& truth, const std::vector<float>& estimate,
                      FrameWork& work) {
    const uint32_t w = truth.width, h = truth.height;
    cv::Mat semantic, occlusion;
    if (setup.occlusion) {
        occlusion = readOcclusion(setup.dir, work.frame, w, h);
        work.nonOccluded.emplace();
    }
    if (setup.semantic) {
        semantic = readSemantic(setup.dir, work.frame, w, h);
        work.classes.resize(kClassGroups.size());
    }
    const std::vector<double>& edges = setup.options->bandEdgesMetres;
    work.bands.resize(edges.size() + 1);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            const float gt = truth.values[i];
            if (!isValidDisparity(gt)) continue;
            work.total.add(estimate[i], gt);
            if (setup.occlusion && occlusion.at<uint8_t>(int(y), int(x)) == 255) work.nonOccluded->add(estimate[i], gt);
            if (setup.semantic) work.classes[classGroupOf(semantic.at<uint8_t>(int(y), int(x)))].add(estimate[i], gt);
            work.bands[bandIndex(edges, setup.calib.depthMetres(gt))].add(estimate[i], gt);
        }
}

void writeFramePictures(const DatasetSetup& setup, const DisparityMap& truth, const std::vector<float>& estimate,
                        uint32_t frame) {
    const uint32_t w = truth.width, h = truth.height;
    const std::string base = setup.pictureDir + "/frames/" + frameName(frame);
    writePng(base + "_estimate.png", colourDisparity(estimate, w, h, setup.colourLo, setup.colourHi));
    writePng(base + "_truth.png", colourDisparity(truth.values, w, h, setup.colourLo, setup.colourHi));
    writePng(base + "_difference.png", differenceImage(estimate, truth.values, w, h));
}

} // namespace

FrameWork evaluateFrame(const DatasetSetup& setup, uint32_t frame) {
    FrameWork work;
    work.frame = frame;
    DisparityMap truth = readGroundTruth(setup.dir, frame);
    const uint32_t w = truth.width, h = truth.height;
    require(w == setup.calib.width && h == setup.calib.height,
            setup.dir + "/calib.txt says " + std::to_string(setup.calib.width) + "x" +
                std::to_string(setup.calib.height) + " but the ground truth of frame " + frameName(frame) + " is " +
                std::to_string(w) + "x" + std::to_string(h));
    const std::vector<float> estimate = estimateDisparity(setup, truth, work);
    accumulateErrors(setup, truth, estimate, work);
    if (setup.options->pictures) writeFramePictures(setup, truth, estimate, frame);
    return work;
}

} // namespace sward

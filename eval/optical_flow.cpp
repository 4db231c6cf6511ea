#include "eval/optical_flow.h"

#include "common/error.h"
#include "eval/number_format.h"

#include <opencv2/video/tracking.hpp>

#include <cassert>
#include <cstring>

namespace sward {

namespace {

struct MethodName {
    FlowMethod method;
    const char* name;
};

constexpr MethodName kMethodNames[] = {
    {FlowMethod::DisUltrafast, "dis-ultrafast"},
    {FlowMethod::DisFast, "dis-fast"},
    {FlowMethod::DisMedium, "dis-medium"},
    {FlowMethod::Farneback, "farneback"},
    {FlowMethod::Files, "files"},
};

cv::Ptr<cv::DISOpticalFlow> createDis(FlowMethod method) {
    const int preset = method == FlowMethod::DisUltrafast ? cv::DISOpticalFlow::PRESET_ULTRAFAST
                       : method == FlowMethod::DisFast    ? cv::DISOpticalFlow::PRESET_FAST
                                                          : cv::DISOpticalFlow::PRESET_MEDIUM;
    return cv::DISOpticalFlow::create(preset);
}

// OpenCV's own defaults (FarnebackOpticalFlow::create()): 5 levels, pyramid scale 0.5, 13 px window, 10
// iterations, polynomial neighbourhood 5 with sigma 1.1; no Gaussian window, no initial flow.
cv::Ptr<cv::FarnebackOpticalFlow> createFarneback() {
    return cv::FarnebackOpticalFlow::create();
}

std::string disDescription(FlowMethod method) {
    const cv::Ptr<cv::DISOpticalFlow> dis = createDis(method);
    return std::string("OpenCV DISOpticalFlow ") + flowMethodName(method) + ": finest scale " +
           std::to_string(dis->getFinestScale()) + ", patch " + std::to_string(dis->getPatchSize()) + " px, stride " +
           std::to_string(dis->getPatchStride()) + " px, " + std::to_string(dis->getGradientDescentIterations()) +
           " gradient-descent iterations, " + std::to_string(dis->getVariationalRefinementIterations()) +
           " variational refinement iterations (alpha " + fixed(dis->getVariationalRefinementAlpha(), 1) + ", gamma " +
           fixed(dis->getVariationalRefinementGamma(), 1) + ", delta " +
           fixed(dis->getVariationalRefinementDelta(), 1) + "), mean normalisation " +
           (dis->getUseMeanNormalization() ? "on" : "off") + ", spatial propagation " +
           (dis->getUseSpatialPropagation() ? "on" : "off") + "; grey 8-bit previews";
}

std::string farnebackDescription() {
    const cv::Ptr<cv::FarnebackOpticalFlow> f = createFarneback();
    return "OpenCV FarnebackOpticalFlow: " + std::to_string(f->getNumLevels()) + " levels, pyramid scale " +
           fixed(f->getPyrScale(), 2) + ", window " + std::to_string(f->getWinSize()) + " px, " +
           std::to_string(f->getNumIters()) + " iterations, polyN " + std::to_string(f->getPolyN()) + ", polySigma " +
           fixed(f->getPolySigma(), 2) + ", flags " + std::to_string(f->getFlags()) + "; grey 8-bit previews";
}

} // namespace

FlowMethod parseFlowMethod(const std::string& text) {
    if (text == "dis") return FlowMethod::DisMedium;
    std::string choices = "dis";
    for (const MethodName& m : kMethodNames) {
        if (text == m.name) return m.method;
        choices += std::string(", ") + m.name;
    }
    throw Error("unknown flow method '" + text + "' (choose " + choices + ")");
}

const char* flowMethodName(FlowMethod method) {
    for (const MethodName& m : kMethodNames)
        if (m.method == method) return m.name;
    return "?";
}

std::string flowMethodDescription(FlowMethod method) {
    switch (method) {
    case FlowMethod::DisUltrafast:
    case FlowMethod::DisFast:
    case FlowMethod::DisMedium:
        return disDescription(method);
    case FlowMethod::Farneback:
        return farnebackDescription();
    case FlowMethod::Files:
        break;
    }
    return "flow files";
}

FlowField computeFlow(FlowMethod method, const cv::Mat& first, const cv::Mat& second) {
    assert(method != FlowMethod::Files);
    require(first.type() == CV_8UC1 && second.type() == CV_8UC1 && first.size() == second.size(),
            "optical flow needs two 8-bit grey images of the same size");
    cv::Mat flow;
    if (method == FlowMethod::Farneback)
        createFarneback()->calc(first, second, flow);
    else
        createDis(method)->calc(first, second, flow);
    require(flow.type() == CV_32FC2 && flow.isContinuous(), "OpenCV returned no 2-channel float flow");
    FlowField field{uint32_t(first.cols), uint32_t(first.rows), std::vector<float>(2 * first.total())};
    std::memcpy(field.uv.data(), flow.ptr<float>(), field.uv.size() * sizeof(float));
    return field;
}

} // namespace sward

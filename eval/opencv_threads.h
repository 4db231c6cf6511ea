// OpenCV parallelises some functions (SGBM stripes, feature pyramids) over its own threads; sward's evaluations
// parallelise over frames instead, so a result can never depend on the thread count. Holding this object makes
// OpenCV single-threaded and restores its setting on exit.
#pragma once

#include <opencv2/core.hpp>

namespace sward {

struct SingleThreadedOpenCV {
    int previous = cv::getNumThreads();
    SingleThreadedOpenCV() { cv::setNumThreads(1); }
    ~SingleThreadedOpenCV() { cv::setNumThreads(previous); }
    SingleThreadedOpenCV(const SingleThreadedOpenCV&) = delete;
    SingleThreadedOpenCV& operator=(const SingleThreadedOpenCV&) = delete;
};

} // namespace sward

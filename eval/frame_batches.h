// How every evaluation runs its frames: several at once, OpenCV single-threaded inside each, results merged in
// frame order. Double sums are then added in the same order whatever the thread count, so every output file is
// bitwise identical for any --threads; batches of `threads` frames bound how many frames' data are alive at once.
#pragma once

#include "common/parallel_for.h"
#include "eval/opencv_threads.h"

#include <opencv2/core.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace sward {

// Calls evaluate(frame) -> Work for every frame on up to `threads` threads (0: every core) and merge(Work&) for
// each result in frame order. An exception of evaluate() is rethrown once its batch has finished (the lowest
// frame's, whatever the schedule); nothing of that batch is merged.
template <class Work, class Evaluate, class Merge>
void evaluateInFrameOrder(const std::vector<uint32_t>& frames, uint32_t threads, Evaluate&& evaluate, Merge&& merge) {
    SingleThreadedOpenCV singleThreaded;
    threads = std::min<uint32_t>(resolveThreadCount(threads), uint32_t(std::max<size_t>(frames.size(), 1)));
    for (size_t begin = 0; begin < frames.size(); begin += threads) {
        const size_t count = std::min<size_t>(threads, frames.size() - begin);
        std::vector<Work> batch(count);
        parallelFor(uint32_t(count), threads, [&](uint32_t k, uint32_t) { batch[k] = evaluate(frames[begin + k]); });
        for (Work& work : batch) merge(work);
    }
}

} // namespace sward

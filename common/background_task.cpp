#include "common/background_task.h"

#include <utility>

namespace sward {

BackgroundTask::~BackgroundTask() {
    if (thread_.joinable()) thread_.join();
}

void BackgroundTask::start(std::function<void()> task) {
    wait();
    thread_ = std::thread([this, task = std::move(task)] {
        try {
            task();
        } catch (...) {
            error_ = std::current_exception(); // read by wait() after join(): the join orders the accesses
        }
    });
}

void BackgroundTask::wait() {
    if (thread_.joinable()) thread_.join();
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

} // namespace sward

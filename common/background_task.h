// One task at a time on a thread of its own, for work that can overlap the caller's next step (sward-render writes a
// frame's files while the GPU renders the next one). start() waits for the task before, wait() rethrows what the task
// threw, so an error stops the run at the next frame as it would have in line. The destructor waits and drops the
// error (the caller is already unwinding from one of its own, or has called wait()).
#pragma once

#include <exception>
#include <functional>
#include <thread>

namespace sward {

class BackgroundTask {
public:
    BackgroundTask() = default;
    ~BackgroundTask();
    BackgroundTask(const BackgroundTask&) = delete;
    BackgroundTask& operator=(const BackgroundTask&) = delete;

    // Waits for the previous task (rethrowing its error), then runs `task` on a new thread.
    void start(std::function<void()> task);
    // Returns when no task is running; rethrows the finished task's exception, once.
    void wait();

private:
    std::thread thread_;
    std::exception_ptr error_;
};

} // namespace sward

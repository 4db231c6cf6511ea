// Commands: command-buffer recording, submission with a timeline semaphore, and deferred destruction.
//
// Every submission gets a serial (the timeline value it signals). Resources that the GPU may still use are
// handed to destroyLater() and freed once the serial of the latest submission has completed; this is the
// per-frame deletion queue of vulkan-guide / Granite, without per-frame fences to juggle.
#pragma once

#include "engine/vk_common.h"

#include <cstdint>
#include <deque>
#include <functional>
#include <vector>

namespace sward {

class Device;

class Submitter {
public:
    explicit Submitter(Device& device);
    ~Submitter();
    Submitter(const Submitter&) = delete;
    Submitter& operator=(const Submitter&) = delete;

    // A primary command buffer in the recording state, freed automatically after its submission completes.
    VkCommandBuffer begin();
    // Ends and submits `cmd`; returns the serial that completes with it. Optional binary semaphores for
    // presentation (viewer).
    uint64_t submit(VkCommandBuffer cmd, VkSemaphore wait = VK_NULL_HANDLE,
                    VkPipelineStageFlags2 waitStage = VK_PIPELINE_STAGE_2_NONE, VkSemaphore signal = VK_NULL_HANDLE);
    // Blocks until `serial` has completed on the GPU, then runs due deferred destructions.
    void wait(uint64_t serial);
    void waitIdle() { wait(lastSubmitted_); }
    uint64_t completed();
    uint64_t lastSubmitted() const { return lastSubmitted_; }

    // Runs `destroy` once everything submitted so far has completed.
    void destroyLater(std::function<void()> destroy);
    // Records, submits and waits for a one-off command buffer (uploads, readbacks, tests).
    void immediate(const std::function<void(VkCommandBuffer)>& record);

private:
    void collect();

    Device& device_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkSemaphore timeline_ = VK_NULL_HANDLE;
    uint64_t lastSubmitted_ = 0;
    struct Pending {
        uint64_t serial;
        VkCommandBuffer cmd;
    };
    std::deque<Pending> inFlight_;
    std::vector<VkCommandBuffer> recording_;
    struct Deferred {
        uint64_t serial;
        std::function<void()> destroy;
    };
    std::deque<Deferred> deferred_;
};

} // namespace sward

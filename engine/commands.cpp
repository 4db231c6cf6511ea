#include "engine/commands.h"

#include "engine/device.h"

#include <algorithm>

namespace sward {

Submitter::Submitter(Device& device) : device_(device) {
    VkCommandPoolCreateInfo poolInfo{
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT,
        .queueFamilyIndex = device.queueFamily(),
    };
    VK_CHECK(vkCreateCommandPool(device.handle(), &poolInfo, nullptr, &pool_));
    VkSemaphoreTypeCreateInfo typeInfo{
        .sType = VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO,
        .semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE,
        .initialValue = 0,
    };
    VkSemaphoreCreateInfo semaphoreInfo{.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, .pNext = &typeInfo};
    VK_CHECK(vkCreateSemaphore(device.handle(), &semaphoreInfo, nullptr, &timeline_));
}

Submitter::~Submitter() {
    // Destructors must not throw: wait for the device directly and release everything.
    vkDeviceWaitIdle(device_.handle());
    for (Deferred& d : deferred_) d.destroy();
    vkDestroySemaphore(device_.handle(), timeline_, nullptr);
    vkDestroyCommandPool(device_.handle(), pool_, nullptr);
}

VkCommandBuffer Submitter::begin() {
    VkCommandBufferAllocateInfo info{
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = pool_,
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1,
    };
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VK_CHECK(vkAllocateCommandBuffers(device_.handle(), &info, &cmd));
    VkCommandBufferBeginInfo begin{
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
        .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT,
    };
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    recording_.push_back(cmd);
    return cmd;
}

uint64_t Submitter::submit(VkCommandBuffer cmd, VkSemaphore wait, VkPipelineStageFlags2 waitStage, VkSemaphore signal) {
    VK_CHECK(vkEndCommandBuffer(cmd));
    recording_.erase(std::remove(recording_.begin(), recording_.end(), cmd), recording_.end());
    uint64_t serial = lastSubmitted_ + 1;
    VkSemaphoreSubmitInfo waitInfo{
        .sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = wait, .stageMask = waitStage};
    VkSemaphoreSubmitInfo signals[2] = {
        {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO,
         .semaphore = timeline_,
         .value = serial,
         .stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT},
        {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO,
         .semaphore = signal,
         .stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT},
    };
    VkCommandBufferSubmitInfo cmdInfo{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmd};
    VkSubmitInfo2 submitInfo{
        .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2,
        .waitSemaphoreInfoCount = wait ? 1u : 0u,
        .pWaitSemaphoreInfos = &waitInfo,
        .commandBufferInfoCount = 1,
        .pCommandBufferInfos = &cmdInfo,
        .signalSemaphoreInfoCount = signal ? 2u : 1u,
        .pSignalSemaphoreInfos = signals,
    };
    VK_CHECK(vkQueueSubmit2(device_.queue(), 1, &submitInfo, VK_NULL_HANDLE));
    lastSubmitted_ = serial;
    inFlight_.push_back({serial, cmd});
    return serial;
}

uint64_t Submitter::completed() {
    uint64_t value = 0;
    VK_CHECK(vkGetSemaphoreCounterValue(device_.handle(), timeline_, &value));
    return value;
}

void Submitter::wait(uint64_t serial) {
    if (serial > 0) {
        VkSemaphoreWaitInfo info{
            .sType = VK_STRUCTURE_TYPE_SEMAPHORE_WAIT_INFO,
            .semaphoreCount = 1,
            .pSemaphores = &timeline_,
            .pValues = &serial,
        };
        VK_CHECK(vkWaitSemaphores(device_.handle(), &info, UINT64_MAX));
    }
    collect();
}

void Submitter::collect() {
    uint64_t done = completed();
    while (!inFlight_.empty() && inFlight_.front().serial <= done) {
        vkFreeCommandBuffers(device_.handle(), pool_, 1, &inFlight_.front().cmd);
        inFlight_.pop_front();
    }
    while (!deferred_.empty() && deferred_.front().serial <= done) {
        deferred_.front().destroy();
        deferred_.pop_front();
    }
}

void Submitter::destroyLater(std::function<void()> destroy) {
    deferred_.push_back({lastSubmitted_, std::move(destroy)});
    collect();
}

void Submitter::immediate(const std::function<void(VkCommandBuffer)>& record) {
    VkCommandBuffer cmd = begin();
    record(cmd);
    wait(submit(cmd));
}

} // namespace sward

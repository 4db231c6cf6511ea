// Shared fixture for GPU tests: a validated Vulkan context; any validation message fails the test.
#pragma once

#include "engine/context.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

namespace sward::test {

class GpuTest : public ::testing::Test {
protected:
    void SetUp() override { ctx = std::make_unique<Context>(DeviceOptions{.validation = true, .quiet = true}); }
    void TearDown() override {
        ctx->submitter.waitIdle();
        EXPECT_EQ(ctx->device.validationMessageCount(), 0u) << "Vulkan validation reported messages (see stderr)";
        ctx.reset();
    }
    std::unique_ptr<Context> ctx;
};

// A fresh, empty temporary folder for one test.
inline std::string tempDir(const std::string& name) {
    auto dir = std::filesystem::temp_directory_path() / ("sward-test-" + name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir.string();
}

} // namespace sward::test

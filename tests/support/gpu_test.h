// Shared fixture for GPU tests: a validated Vulkan context; any validation message fails the test.
#pragma once

#include "engine/context.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <sys/wait.h>

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

inline std::string readFile(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

// Runs sward-render with `args` (validation on, quiet); returns its exit status and its stderr in `err`.
inline int runSwardRender(const std::string& args, std::string& err) {
    const std::string dir = tempDir("render-log");
    const std::string command =
        SWARD_RENDER_EXE " " + args + " --validation --quiet >" + dir + "/out.txt 2>" + dir + "/err.txt";
    const int status = std::system(command.c_str());
    err = readFile(dir + "/err.txt");
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

} // namespace sward::test

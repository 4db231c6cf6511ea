// Shared fixture for GPU tests: a validated Vulkan context; any validation message fails the test.
#pragma once

#include "engine/context.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
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

// Writes the scene text `json` to `dir`/`name`.json and returns that path.
inline std::string writeSceneFile(const std::string& dir, const std::string& name, const std::string& json) {
    const std::string path = dir + "/" + name + ".json";
    std::ofstream(path) << json;
    return path;
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

// Every file of the dataset `a` (but its manifests, dataset.json, the scene's copy and the relative paths in `skip`)
// compared bytewise with the same file of `b`, each difference a test failure naming the file; returns how many were
// compared (so a test can check that the files it means were there).
inline size_t expectSameRunFiles(const std::string& a, const std::string& b, const std::set<std::string>& skip = {}) {
    size_t files = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(a)) {
        const std::string relative = std::filesystem::relative(entry.path(), a).string();
        if (!entry.is_regular_file() || relative.starts_with("manifest") || relative == "dataset.json" ||
            relative == "scene.json" || skip.contains(relative))
            continue;
        EXPECT_EQ(readFile(entry.path().string()), readFile(b + "/" + relative)) << relative;
        ++files;
    }
    return files;
}

} // namespace sward::test

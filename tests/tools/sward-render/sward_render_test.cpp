// sward-render as a user runs it: output files, determinism across lavapipe thread counts, clear errors.
#include "gpu_test.h"
#include "io/image_files.h"

#include <array>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <sys/wait.h>
#include <vector>

using sward::test::tempDir;

namespace {

struct RunResult {
    int exitCode = -1;
    std::string err;
};

// Runs sward-render with `args` (shell-quoted by the caller) and an environment prefix; captures stderr.
RunResult runRender(const std::string& args, const std::string& env = "") {
    std::string errFile = tempDir("stderr") + "/err.txt";
    std::string command = env + " " SWARD_RENDER_EXE " " + args + " >/dev/null 2>" + errFile;
    int status = std::system(command.c_str());
    std::ifstream file(errFile);
    std::stringstream text;
    text << file.rdbuf();
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

std::string readFile(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

int countLines(const std::string& s, const std::string& needle) {
    int n = 0;
    std::istringstream lines(s);
    for (std::string line; std::getline(lines, line);) n += line.find(needle) != std::string::npos;
    return n;
}

const std::string kSmall = "--resolution 160x120 --samples 4 --validation";

} // namespace

TEST(SwardRender, WritesColourDepthAndPreview) {
    std::string out = tempDir("cli-out");
    RunResult r = runRender(kSmall + " --out " + out);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* file : {"/left/000000.exr", "/depth/000000.exr", "/preview/000000.png"})
        EXPECT_TRUE(std::filesystem::file_size(out + file) > 0) << file;
    EXPECT_EQ(countLines(r.err, "validation"), 1) << "only the device line may mention validation:\n" << r.err;
}

TEST(SwardRender, OutputIsBitwiseIdenticalWithOneOrManyLavapipeThreads) {
    std::string a = tempDir("cli-threads1"), b = tempDir("cli-threadsN"), c = tempDir("cli-threadsN2");
    ASSERT_EQ(runRender(kSmall + " --out " + a, "LP_NUM_THREADS=1").exitCode, 0);
    ASSERT_EQ(runRender(kSmall + " --out " + b).exitCode, 0);
    ASSERT_EQ(runRender(kSmall + " --out " + c, "LP_NUM_THREADS=3").exitCode, 0);
    for (const char* file : {"/left/000000.exr", "/depth/000000.exr", "/preview/000000.png"}) {
        std::string reference = readFile(a + file);
        ASSERT_FALSE(reference.empty()) << file;
        EXPECT_TRUE(reference == readFile(b + file)) << file << " differs between 1 thread and the default";
        EXPECT_TRUE(reference == readFile(c + file)) << file << " differs between 1 and 3 threads";
    }
}

TEST(SwardRender, UnknownDeviceIsOneClearError) {
    RunResult r = runRender("--device no-such-gpu --out " + tempDir("cli-dev"));
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(countLines(r.err, "error"), 1) << r.err;
    EXPECT_NE(r.err.find("no-such-gpu"), std::string::npos) << r.err;
}

TEST(SwardRender, UnwritableOutputIsOneClearError) {
    std::string dir = tempDir("cli-unwritable");
    std::ofstream(dir + "/file") << "x"; // a regular file cannot hold an output folder
    RunResult r = runRender("--out " + dir + "/file/out");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(countLines(r.err, "error"), 1) << r.err;
    EXPECT_NE(r.err.find("file/out"), std::string::npos) << r.err;
    EXPECT_EQ(countLines(r.err, "device"), 0) << "failed before touching the GPU:\n" << r.err;
}

TEST(SwardRender, BadResolutionIsOneClearError) {
    for (const char* bad : {"12x", "0x10", "640*480", "99999x10", "axb"}) {
        RunResult r = runRender(std::string("--resolution '") + bad + "' --out " + tempDir("cli-res"));
        EXPECT_NE(r.exitCode, 0) << bad;
        EXPECT_EQ(countLines(r.err, "error"), 1) << bad << ": " << r.err;
        EXPECT_NE(r.err.find("resolution"), std::string::npos) << r.err;
    }
}

TEST(SwardRender, MissingOrMalformedSceneIsOneClearError) {
    std::string dir = tempDir("cli-scene");
    RunResult missing = runRender(dir + "/nope.json --out " + dir + "/o");
    EXPECT_NE(missing.exitCode, 0);
    EXPECT_NE(missing.err.find("nope.json"), std::string::npos) << missing.err;
    std::ofstream(dir + "/bad.json") << R"({"terrain": {"amplitude": "tall"}})";
    RunResult malformed = runRender(dir + "/bad.json --out " + dir + "/o");
    EXPECT_NE(malformed.exitCode, 0);
    EXPECT_EQ(countLines(malformed.err, "error"), 1) << malformed.err;
    EXPECT_NE(malformed.err.find("terrain.amplitude"), std::string::npos) << malformed.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/o/left/000000.exr")) << "nothing is written for a bad scene";
}

TEST(SwardRender, AGrassMapOutsideTheScenesFolderNeedsAllowAssets) {
    const std::string dir = std::filesystem::canonical(tempDir("cli-assets")).string();
    std::filesystem::create_directories(dir + "/scene");
    std::filesystem::create_directories(dir + "/maps");
    sward::writePng8(dir + "/maps/m.png", 8, 8, 3, std::vector<uint8_t>(8 * 8 * 3, 0)); // no plants: a fast run
    std::ofstream(dir + "/scene/s.json") << R"({"terrain": {"size": 50, "spacing": 2},
        "render": {"resolution": [160, 120], "samples": 1}, "grass_map": "../maps/m.png"})";
    RunResult refused = runRender(dir + "/scene/s.json --out " + dir + "/o");
    EXPECT_NE(refused.exitCode, 0);
    EXPECT_EQ(countLines(refused.err, "error"), 1) << refused.err;
    EXPECT_NE(refused.err.find("'grass_map': '../maps/m.png' resolves to " + dir +
                               "/maps/m.png, outside the scene's "
                               "folder " +
                               dir + "/scene (allow with --allow-assets DIR)"),
              std::string::npos)
        << refused.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/o")) << "a refused asset writes nothing";
    RunResult allowed =
        runRender(dir + "/scene/s.json --validation --allow-assets " + dir + "/maps --out " + dir + "/o");
    ASSERT_EQ(allowed.exitCode, 0) << allowed.err;
    EXPECT_TRUE(std::filesystem::exists(dir + "/o/preview/000000.png"));
}

namespace {

// The scene of the resume tests (stereo, vegetation, a rover), small and with one sample: fast on lavapipe.
const std::string kResumeScene = std::string(SWARD_TEST_DATA_DIR) + "/dataset_scene.json --samples 1 --quiet";

// Every file under `dir` with its bytes, so "the folder is unchanged" is one comparison.
std::map<std::string, std::string> snapshot(const std::string& dir) {
    std::map<std::string, std::string> files;
    if (!std::filesystem::exists(dir)) return files;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
        files[std::filesystem::relative(entry.path(), dir).string()] =
            entry.is_directory() ? "<folder>" : readFile(entry.path().string());
    return files;
}

void expectSameFramesAs(const std::string& reference, const std::string& dir) {
    std::map<std::string, std::string> a = snapshot(reference), b = snapshot(dir);
    a.erase("manifest.json");
    b.erase("manifest.json");
    EXPECT_TRUE(a == b) << dir << " differs from a fresh run in " << reference;
}

} // namespace

TEST(SwardRender, AResolutionChangeIsRefusedAndOverwriteRendersAFreshDataset) {
    const std::string out = tempDir("cli-resume-res"), fresh = tempDir("cli-resume-res-fresh");
    ASSERT_EQ(runRender(kResumeScene + " --frames 0:1 --resolution 32x24 --out " + out).exitCode, 0);
    const auto before = snapshot(out);
    RunResult r = runRender(kResumeScene + " --frames 0:1 --resolution 40x30 --out " + out);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(countLines(r.err, "error"), 1) << r.err;
    EXPECT_NE(r.err.find("was rendered with --resolution 32x24, this run asks for --resolution 40x30; use "
                         "--overwrite"), std::string::npos) << r.err;
    EXPECT_TRUE(snapshot(out) == before) << "the refused run changed the folder";

    ASSERT_EQ(runRender(kResumeScene + " --frames 0:1 --resolution 40x30 --overwrite --out " + out).exitCode, 0);
    ASSERT_EQ(runRender(kResumeScene + " --frames 0:1 --resolution 40x30 --out " + fresh).exitCode, 0);
    expectSameFramesAs(fresh, out);
}

TEST(SwardRender, NoVegetationAfterAVegetatedRunIsRefused) {
    const std::string out = tempDir("cli-resume-veg"), fresh = tempDir("cli-resume-veg-fresh");
    ASSERT_EQ(runRender(kResumeScene + " --frames 0:1 --resolution 32x24 --out " + out).exitCode, 0);
    const auto before = snapshot(out);
    RunResult r = runRender(kResumeScene + " --frames 0:1 --resolution 32x24 --no-vegetation --out " + out);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("was rendered with vegetation, this run asks for --no-vegetation"), std::string::npos)
        << r.err;
    EXPECT_TRUE(snapshot(out) == before) << "the refused run changed the folder";

    ASSERT_EQ(runRender(kResumeScene + " --frames 0:1 --resolution 32x24 --no-vegetation --overwrite --out " + out)
                  .exitCode, 0);
    ASSERT_EQ(runRender(kResumeScene + " --frames 0:1 --resolution 32x24 --no-vegetation --out " + fresh).exitCode, 0);
    expectSameFramesAs(fresh, out);
}

TEST(SwardRender, AnUnknownDeviceLeavesTheOutputFolderAsItWas) {
    const std::string parent = tempDir("cli-dev-nothing");
    RunResult missing = runRender(kResumeScene + " --device no-such-gpu --out " + parent + "/new");
    EXPECT_EQ(missing.exitCode, 1);
    EXPECT_FALSE(std::filesystem::exists(parent + "/new")) << "not even an empty folder";
    std::ofstream(parent + "/user.tmp") << "mine";
    RunResult existing = runRender(kResumeScene + " --device no-such-gpu --out " + parent);
    EXPECT_EQ(existing.exitCode, 1);
    EXPECT_EQ(snapshot(parent), (std::map<std::string, std::string>{{"user.tmp", "mine"}}));
}

TEST(SwardRender, AFailureMidRunLeavesTheFolderAsFound) {
    const std::string out = tempDir("cli-mid-run");
    ASSERT_EQ(runRender(kResumeScene + " --frames 0:1 --resolution 32x24 --out " + out).exitCode, 0);
    // A folder where frame 2's colour file goes makes the run fail after frame 1 was written.
    std::filesystem::create_directories(out + "/left/000002.exr");
    std::ofstream(out + "/notes.tmp") << "user file";
    const auto before = snapshot(out);
    RunResult r = runRender(kResumeScene + " --frames 0:3 --resolution 32x24 --out " + out);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(countLines(r.err, "error"), 1) << r.err;
    EXPECT_NE(r.err.find("cannot write '" + out + "/left/000002.exr'"), std::string::npos) << r.err;
    EXPECT_TRUE(snapshot(out) == before) << "frame 1 and the manifest of the failed run must be gone";
}

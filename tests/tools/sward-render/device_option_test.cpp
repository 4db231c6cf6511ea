// sward-render's --device and --list-devices on a machine of two Vulkan devices: lavapipe's driver file given to
// the Vulkan loader twice (VK_DRIVER_FILES) enumerates two devices of one name and one UUID, the hardest case for
// the choice (docs/release.md, "GPU portability").
#include "gpu_test.h"

#include <filesystem>
#include <string>
#include <sys/wait.h>

using sward::test::readFile;
using sward::test::tempDir;

namespace {

struct RenderRun {
    int exitCode = -1;
    std::string out, err;
};

RenderRun runRender(const std::string& env, const std::string& args) {
    const std::string dir = tempDir("device-option-log");
    const std::string command = env + " " SWARD_RENDER_EXE " " + args + " >" + dir + "/out.txt 2>" + dir + "/err.txt";
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, readFile(dir + "/out.txt"), readFile(dir + "/err.txt")};
}

// Two copies of lavapipe's ICD file, as the loader's VK_DRIVER_FILES; empty when Mesa's lavapipe is not installed.
std::string twoLavapipeDrivers() {
    const std::filesystem::path icds = "/usr/share/vulkan/icd.d";
    if (!std::filesystem::is_directory(icds)) return "";
    for (const auto& entry : std::filesystem::directory_iterator(icds)) {
        if (entry.path().filename().string().rfind("lvp_icd", 0) != 0) continue;
        const std::string dir = tempDir("two-drivers");
        std::filesystem::copy_file(entry.path(), dir + "/a.json");
        std::filesystem::copy_file(entry.path(), dir + "/b.json");
        return "VK_DRIVER_FILES=" + dir + "/a.json:" + dir + "/b.json VK_ICD_FILENAMES=" + dir + "/a.json:" + dir +
               "/b.json";
    }
    return "";
}

const std::string kFrame =
    SWARD_TEST_DATA_DIR "/dataset_scene.json --resolution 64x48 --frames 0:1 --validation --quiet";

} // namespace

TEST(SwardRenderDevice, TwoDevicesAreListedAndChosenByIndexNeverByAnAmbiguousName) {
    const std::string env = twoLavapipeDrivers();
    if (env.empty()) GTEST_SKIP() << "no lavapipe ICD file in /usr/share/vulkan/icd.d";
    const RenderRun list = runRender(env, "--list-devices");
    ASSERT_EQ(list.exitCode, 0) << list.err;
    EXPECT_EQ(list.out.rfind("#0  ", 0), 0u) << list.out;
    EXPECT_NE(list.out.find("(automatic choice)\n#1  "), std::string::npos) << list.out;

    const RenderRun byName = runRender(env, kFrame + " --device llvmpipe --out " + tempDir("device-by-name"));
    EXPECT_EQ(byName.exitCode, 1);
    EXPECT_NE(byName.err.find("matches 2 devices of the same type (#0 'llvmpipe"), std::string::npos) << byName.err;

    // The second device renders the very bytes of the first.
    const std::string first = tempDir("device-0"), second = tempDir("device-1");
    const RenderRun a = runRender(env, kFrame + " --device '#0' --out " + first);
    ASSERT_EQ(a.exitCode, 0) << a.err;
    const RenderRun b = runRender("SWARD_DEVICE=1 " + env, kFrame + " --out " + second);
    ASSERT_EQ(b.exitCode, 0) << b.err;
    EXPECT_GT(sward::test::expectSameRunFiles(first, second), 5u);
}

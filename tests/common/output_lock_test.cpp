// One writer per output folder: a second writer fails at once naming the holder's pid, the shards of one run share
// the folder, a dead process's lock file is taken over, the last holder leaves no lock file and a link in its
// place is refused.
#include "common/output_lock.h"

#include "common/error.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

using namespace sward;
namespace fs = std::filesystem;

namespace {

// The error a second OutputLock on `dir` throws ("" when it took the lock).
std::string secondLockError(const std::string& dir, OutputLock::Mode mode) {
    return test::errorOf([&] { OutputLock second(dir, mode); });
}

} // namespace

TEST(OutputLock, ASecondWriterFailsAtOnceNamingTheHoldersPid) {
    const std::string dir = test::tempDir().string();
    OutputLock first(dir, OutputLock::Mode::Exclusive);
    const std::string pid = "pid " + std::to_string(::getpid());
    for (OutputLock::Mode mode : {OutputLock::Mode::Exclusive, OutputLock::Mode::Shared}) {
        const std::string error = secondLockError(dir, mode);
        EXPECT_NE(error.find("is being written by another sward process (" + pid + ")"), std::string::npos) << error;
    }
}

TEST(OutputLock, ShardsShareTheFolderAndExcludeEveryOtherWriter) {
    const std::string dir = test::tempDir().string();
    std::optional<OutputLock> shard0(std::in_place, dir, OutputLock::Mode::Shared);
    EXPECT_EQ(secondLockError(dir, OutputLock::Mode::Shared), "");
    EXPECT_NE(secondLockError(dir, OutputLock::Mode::Exclusive), "");
    OutputLock shard1(dir, OutputLock::Mode::Shared);
    shard0.reset(); // one shard done: the other still holds the folder, and its lock file stays
    EXPECT_TRUE(fs::exists(dir + "/" + kOutputLockFile));
    EXPECT_NE(secondLockError(dir, OutputLock::Mode::Exclusive), "");
}

TEST(OutputLock, TheLastHolderLeavesNoLockFile) {
    const std::string dir = test::tempDir().string();
    {
        OutputLock lock(dir, OutputLock::Mode::Exclusive);
        EXPECT_EQ(std::stol(test::readText(dir + "/" + kOutputLockFile)), long(::getpid()));
    }
    EXPECT_TRUE(fs::is_empty(dir));
    EXPECT_EQ(secondLockError(dir, OutputLock::Mode::Exclusive), "");
}

TEST(OutputLock, ADeadProcesssLockFileIsTakenOver) {
    const std::string dir = test::tempDir().string();
    const long dead = test::deadPid();
    std::ofstream(dir + "/" + kOutputLockFile) << dead << "\n";
    OutputLock lock(dir, OutputLock::Mode::Exclusive);
    EXPECT_EQ(std::stol(test::readText(dir + "/" + kOutputLockFile)), long(::getpid()));
}

TEST(OutputLock, ALinkInPlaceOfTheLockFileIsRefusedNotFollowed) {
    const std::string dir = test::tempDir().string();
    fs::create_directories(dir + "/out");
    std::ofstream(dir + "/elsewhere") << "keep\n";
    fs::create_symlink(dir + "/elsewhere", dir + "/out/" + kOutputLockFile);
    const std::string error = secondLockError(dir + "/out", OutputLock::Mode::Exclusive);
    EXPECT_NE(error.find("is a symbolic link"), std::string::npos) << error;
    EXPECT_EQ(test::readText(dir + "/elsewhere"), "keep\n");
}

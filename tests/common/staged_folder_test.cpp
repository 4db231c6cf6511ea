// Staged output folders (sward-export, sward-eval): whole or not at all, never through a link, one writer, and the
// staging folders of dead processes removed.
#include "common/staged_folder.h"

#include "common/error.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <linux/fs.h>
#include <map>
#include <sstream>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

using namespace sward;
namespace fs = std::filesystem;

namespace {

void writeFile(const std::string& path, const std::string& text) {
    fs::create_directories(fs::path(path).parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

// Every entry below `dir` with its content ("<dir>" for folders, "-> target" for links).
std::map<std::string, std::string> treeOf(const std::string& dir) {
    std::map<std::string, std::string> tree;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) {
        const std::string name = fs::relative(e.path(), dir).string();
        tree[name] = e.is_symlink()     ? "-> " + fs::read_symlink(e.path()).string()
                     : e.is_directory() ? "<dir>"
                                        : test::readText(e.path().string());
    }
    return tree;
}

std::string commitError(StagedFolder& staged) {
    return test::errorOf([&] { staged.commit(); });
}

// Makes `dir` refuse new entries even for root (the immutable flag), or read-only for anyone else; false where
// neither is possible (a file system without the flag).
bool refuseEntries(const std::string& dir, bool refuse) {
    if (::geteuid() != 0) return ::chmod(dir.c_str(), refuse ? 0555 : 0755) == 0;
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
    int flags = 0;
    bool ok = fd >= 0 && ::ioctl(fd, FS_IOC_GETFLAGS, &flags) == 0;
    flags = refuse ? (flags | FS_IMMUTABLE_FL) : (flags & ~FS_IMMUTABLE_FL);
    ok = ok && ::ioctl(fd, FS_IOC_SETFLAGS, &flags) == 0;
    if (fd >= 0) ::close(fd);
    return ok;
}

} // namespace

TEST(StagedFolder, CommitMovesTheFilesInAndLeavesForeignFilesAlone) {
    const std::string dir = test::tempDir().string(), out = dir + "/out";
    writeFile(out + "/000000/im0.png", "old");
    writeFile(out + "/notes.txt", "mine");
    {
        StagedFolder staged(out, "output folder");
        writeFile(staged.path() + "/000000/im0.png", "new");
        writeFile(staged.path() + "/000001/im0.png", "new 1");
        staged.commit();
    }
    EXPECT_EQ(treeOf(out), (std::map<std::string, std::string>{{"000000", "<dir>"},
                                                               {"000000/im0.png", "new"},
                                                               {"000001", "<dir>"},
                                                               {"000001/im0.png", "new 1"},
                                                               {"notes.txt", "mine"}}));
    EXPECT_EQ(treeOf(dir).size(), 6u) << "staging folder or lock file left behind";
}

TEST(StagedFolder, ALinkInTheFinalFolderIsRefusedBeforeAnyWork) {
    const std::string dir = test::tempDir().string(), out = dir + "/exp";
    fs::create_directories(dir + "/elsewhere");
    writeFile(out + "/000003/im0.png", "old");
    fs::create_symlink(dir + "/elsewhere", out + "/000003/extra");
    const auto before = treeOf(dir);
    try {
        StagedFolder staged(out, "output folder");
        FAIL() << "a link in the output folder was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("'" + out + "/000003/extra' is a symbolic link"), std::string::npos)
            << e.what();
    }
    EXPECT_EQ(treeOf(dir), before);
}

TEST(StagedFolder, ALinkMadeDuringTheRunIsRefusedAtCommitAndNothingMoves) {
    const std::string dir = test::tempDir().string(), out = dir + "/exp";
    fs::create_directories(dir + "/elsewhere");
    fs::create_directories(out);
    StagedFolder staged(out, "output folder");
    fs::create_symlink(dir + "/elsewhere", out + "/000000");
    const auto before = treeOf(out);
    writeFile(staged.path() + "/calib.txt", "calib");
    writeFile(staged.path() + "/000000/im0.png", "new");
    const std::string error = commitError(staged);
    EXPECT_NE(error.find("'" + out + "/000000' is a symbolic link"), std::string::npos) << error;
    EXPECT_EQ(treeOf(out), before);
    EXPECT_TRUE(fs::is_empty(dir + "/elsewhere"));
}

TEST(StagedFolder, AFileWhereAFolderGoesFailsBeforeAnythingIsReplaced) {
    const std::string dir = test::tempDir().string(), out = dir + "/exp";
    writeFile(out + "/000000/im0.png", "old");
    writeFile(out + "/000001", "a file");
    const auto before = treeOf(out);
    {
        StagedFolder staged(out, "output folder");
        writeFile(staged.path() + "/000000/im0.png", "new");
        writeFile(staged.path() + "/000001/im0.png", "new");
        const std::string error = commitError(staged);
        EXPECT_NE(error.find("'" + out + "/000001' is a file where the output has a folder"), std::string::npos)
            << error;
    }
    EXPECT_EQ(treeOf(out), before);
}

TEST(StagedFolder, AMoveThatFailsPartWayIsRolledBack) {
    const std::string dir = test::tempDir().string(), out = dir + "/exp";
    writeFile(out + "/a.txt", "old a");
    writeFile(out + "/b/x.txt", "old x");
    const auto before = treeOf(out);
    if (!refuseEntries(out + "/b", true)) GTEST_SKIP() << "cannot make a folder refuse new entries here";
    std::string error;
    {
        StagedFolder staged(out, "output folder");
        writeFile(staged.path() + "/a.txt", "new a");   // swapped in first (names in order)...
        writeFile(staged.path() + "/a0/y.txt", "new");  // ...a new folder moved in...
        writeFile(staged.path() + "/b/z.txt", "new z"); // ...then b/ refuses the new file
        error = commitError(staged);
    }
    refuseEntries(out + "/b", false);
    EXPECT_NE(error.find("cannot move"), std::string::npos) << error;
    EXPECT_EQ(treeOf(out), before);
}

TEST(StagedFolder, TheStagingFoldersOfDeadProcessesAreRemoved) {
    const std::string dir = test::tempDir().string(), out = dir + "/exp";
    const std::string stale = dir + "/.exp.sward-" + std::to_string(test::deadPid()) + ".tmp";
    const std::string live = dir + "/.exp.sward-" + std::to_string(::getppid()) + ".tmp";
    const std::string other = dir + "/.other.sward-" + std::to_string(test::deadPid()) + ".tmp";
    for (const std::string& folder : {stale, live, other}) writeFile(folder + "/000000/im0.png", "half");
    {
        StagedFolder staged(out, "output folder");
        staged.commit();
    }
    EXPECT_FALSE(fs::exists(stale));
    EXPECT_TRUE(fs::exists(live)) << "a running process's staging folder was removed";
    EXPECT_TRUE(fs::exists(other)) << "another folder's staging folder was removed";
}

TEST(StagedFolder, ADerivedFolderThatIsALinkIsRefusedAChosenOneIsWritten) {
    const std::string dir = test::tempDir().string();
    fs::create_directories(dir + "/elsewhere");
    fs::create_directories(dir + "/dataset");
    fs::create_symlink(dir + "/elsewhere", dir + "/dataset/eval");
    try {
        StagedFolder staged(dir + "/dataset/eval", "report folder", false);
        FAIL() << "a derived folder that is a link was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("is a symbolic link"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(fs::is_empty(dir + "/elsewhere"));
    {
        StagedFolder staged(dir + "/dataset/eval", "report folder", true); // --out given by the user
        writeFile(staged.path() + "/report.md", "report");
        staged.commit();
    }
    EXPECT_EQ(test::readText(dir + "/elsewhere/report.md"), "report");
    EXPECT_TRUE(fs::is_symlink(dir + "/dataset/eval"));
}

TEST(StagedFolder, ASecondWriterOfTheFolderFailsAndAFailedRunLeavesNothing) {
    const std::string dir = test::tempDir().string(), out = dir + "/new/exp";
    {
        StagedFolder first(out, "output folder");
        try {
            StagedFolder second(out, "output folder");
            FAIL() << "two writers of one folder";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("pid " + std::to_string(::getpid())), std::string::npos) << e.what();
        }
        writeFile(first.path() + "/half.txt", "half");
    } // no commit
    EXPECT_TRUE(fs::is_empty(dir)) << "the folders the run made, its lock file or its staging folder were left";
}

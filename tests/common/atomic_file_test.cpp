// The one atomic byte writer: complete files only under final names, no temporaries left, one clear error when
// the disk refuses a write, and only sward's own dead temporaries cleaned up.
#include "common/atomic_file.h"

#include "common/error.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

using namespace sward;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> namesIn(const std::string& dir) {
    std::vector<std::string> names;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
    std::sort(names.begin(), names.end());
    return names;
}

// Runs `body` in a child process whose file size limit is `limit` bytes (writes past it fail with EFBIG, the
// way a full disk fails them with ENOSPC); returns the error message the child saw, or "" when none.
std::string errorWithFileSizeLimit(rlim_t limit, const std::function<void()>& body) {
    int pipeFds[2];
    if (pipe(pipeFds) != 0) return "pipe failed";
    const pid_t pid = fork();
    if (pid == 0) {
        close(pipeFds[0]);
        std::signal(SIGXFSZ, SIG_IGN); // the write then fails with EFBIG instead of killing the process
        rlimit rl{limit, limit};
        setrlimit(RLIMIT_FSIZE, &rl);
        std::string message;
        try {
            body();
        } catch (const Error& e) {
            message = e.what();
        }
        (void)!write(pipeFds[1], message.data(), message.size());
        _exit(0);
    }
    close(pipeFds[1]);
    std::string message;
    char buffer[512];
    for (ssize_t n; (n = read(pipeFds[0], buffer, sizeof buffer)) > 0;) message.append(buffer, size_t(n));
    close(pipeFds[0]);
    waitpid(pid, nullptr, 0);
    return message;
}

} // namespace

TEST(AtomicFile, WritesTheBytesAndLeavesNoTemporary) {
    const std::string dir = test::tempDir().string();
    writeTextAtomically(dir + "/a.txt", "hello");
    EXPECT_EQ(test::readText(dir + "/a.txt"), "hello");
    writeTextAtomically(dir + "/a.txt", "replaced");
    EXPECT_EQ(test::readText(dir + "/a.txt"), "replaced");
    EXPECT_EQ(namesIn(dir), std::vector<std::string>{"a.txt"});
}

TEST(AtomicFile, AFailedWriteIsOneClearErrorAndLeavesNoFileUnderTheName) {
    const std::string dir = test::tempDir().string();
    const std::string big(64 * 1024, 'x');
    const std::string message = errorWithFileSizeLimit(4096, [&] { writeTextAtomically(dir + "/big.bin", big); });
    EXPECT_EQ(message, "cannot write '" + dir +
                           "/big.bin': file too large for the file system or the process's "
                           "file size limit");
    EXPECT_TRUE(namesIn(dir).empty()) << "no partial file and no temporary";
}

TEST(AtomicFile, AFailedReplacementKeepsTheOldFileWhole) {
    const std::string dir = test::tempDir().string();
    writeTextAtomically(dir + "/keep.bin", "old content");
    const std::string big(64 * 1024, 'y');
    const std::string message = errorWithFileSizeLimit(4096, [&] { writeTextAtomically(dir + "/keep.bin", big); });
    EXPECT_NE(message.find("cannot write '" + dir + "/keep.bin': file too large"), std::string::npos) << message;
    EXPECT_EQ(test::readText(dir + "/keep.bin"), "old content");
    EXPECT_EQ(namesIn(dir), std::vector<std::string>{"keep.bin"});
}

TEST(AtomicFile, AMissingFolderIsNamedInTheError) {
    const std::string dir = test::tempDir().string();
    try {
        writeTextAtomically(dir + "/nope/a.txt", "x");
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "cannot write '" + dir + "/nope/a.txt': no such file or folder");
    }
}

TEST(AtomicFile, CreateFileExclusivelyNeverReplaces) {
    const std::string dir = test::tempDir().string();
    EXPECT_TRUE(createFileExclusively(dir + "/once.json", "first"));
    EXPECT_FALSE(createFileExclusively(dir + "/once.json", "second"));
    EXPECT_EQ(test::readText(dir + "/once.json"), "first");
    EXPECT_EQ(namesIn(dir), std::vector<std::string>{"once.json"});
}

TEST(AtomicFile, TemporaryNamesAreRecognisedExactly) {
    long pid = 0;
    EXPECT_EQ(temporaryPathFor("out/left/000001.exr", 42), "out/left/.000001.exr.sward-42.tmp");
    EXPECT_TRUE(isSwardTemporary(".000001.exr.sward-42.tmp", pid));
    EXPECT_EQ(pid, 42);
    for (const char* foreign :
         {"notes.tmp", "000001.exr.tmp", ".x.sward-.tmp", ".x.sward-12a.tmp", ".sward-1.tmp", ".x.sward-1.tmp.bak"})
        EXPECT_FALSE(isSwardTemporary(foreign, pid)) << foreign;
}

TEST(AtomicFile, OnlyTheTemporariesOfDeadProcessesAreRemoved) {
    const std::string dir = test::tempDir().string();
    const pid_t child = fork(); // a process that is surely gone: its pid names a stale temporary
    if (child == 0) _exit(0);
    waitpid(child, nullptr, 0);
    const std::string stale = fs::path(temporaryPathFor(dir + "/a.png", child)).filename();
    const std::string live = fs::path(temporaryPathFor(dir + "/b.png", 1)).filename(); // pid 1 always runs
    for (const std::string& name : {stale, live, std::string("user.tmp"), std::string(".hidden.tmp")})
        std::ofstream(dir + "/" + name) << "x";
    removeStaleTemporaries(dir);
    EXPECT_EQ(namesIn(dir), (std::vector<std::string>{live, ".hidden.tmp", "user.tmp"}));
}

TEST(AtomicFile, ErrorReasonsAreWordedForPeople) {
    EXPECT_EQ(ioErrorReason(ENOSPC), "no space left on device");
    EXPECT_EQ(ioErrorReason(EIO), "input/output error");
    EXPECT_EQ(ioErrorReason(EDQUOT), "disk quota exceeded");
}

// A link swapped in for a dataset's folder while a render runs: below an OutputRoot it is refused at the next write
// and nothing reaches the link's target; a link in place of the file itself is replaced, not written through.
TEST(AtomicFile, BelowAnOutputRootNoLinkIsFollowed) {
    const std::string dir = test::tempDir().string(), out = dir + "/out", elsewhere = dir + "/elsewhere";
    fs::create_directories(out + "/left");
    fs::create_directories(elsewhere);
    const OutputRoot root(out);
    writeTextAtomically(out + "/left/a.txt", "in place");
    EXPECT_EQ(test::readText(out + "/left/a.txt"), "in place");

    fs::remove_all(out + "/left");
    fs::create_directory_symlink(elsewhere, out + "/left");
    EXPECT_EQ(test::errorOf([&] { writeTextAtomically(out + "/left/b.txt", "x"); }),
              "cannot write '" + out + "/left/b.txt': a folder on its way is a symbolic link or not a folder (sward " +
                  "writes through no link in an output folder)");
    EXPECT_THROW(createFileExclusively(out + "/left/c.txt", "x"), Error);
    EXPECT_TRUE(namesIn(elsewhere).empty());

    std::ofstream(elsewhere + "/target.txt") << "keep";
    fs::create_symlink(elsewhere + "/target.txt", out + "/name.txt");
    writeTextAtomically(out + "/name.txt", "replaced");
    EXPECT_FALSE(fs::is_symlink(out + "/name.txt"));
    EXPECT_EQ(test::readText(out + "/name.txt"), "replaced");
    EXPECT_EQ(test::readText(elsewhere + "/target.txt"), "keep");
}

// The --out a user names may itself be a link (their choice): the root is opened through it.
TEST(AtomicFile, AnOutputRootMayItselfBeALink) {
    const std::string dir = test::tempDir().string();
    fs::create_directories(dir + "/real/left");
    fs::create_directory_symlink(dir + "/real", dir + "/out");
    const OutputRoot root(dir + "/out/");
    writeTextAtomically(dir + "/out/left/a.txt", "through the user's link");
    EXPECT_EQ(test::readText(dir + "/real/left/a.txt"), "through the user's link");
}

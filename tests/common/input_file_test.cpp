// The input door (common/input_file.h): whole regular files only, refused before a byte is read otherwise.
#include "common/input_file.h"

#include "common/error.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sys/stat.h>
#include <unistd.h>

using namespace sward;

namespace {} // namespace

TEST(InputFile, ReadsAWholeRegularFile) {
    const auto dir = test::tempDir();
    std::ofstream(dir / "a.json", std::ios::binary) << "{\"a\": 1}";
    EXPECT_EQ(readInputFile((dir / "a.json").string(), "scene file"), "{\"a\": 1}");
    EXPECT_EQ(readInputBytes((dir / "a.json").string(), "scene file").size(), 8u);
    std::filesystem::remove_all(dir);
}

TEST(InputFile, AFifoIsRefusedWithoutBlocking) {
    const auto dir = test::tempDir();
    const std::string fifo = (dir / "scene.json").string();
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_EQ(test::errorOf([&] { readInputFile(fifo, "scene file"); }),
              fifo + ": the scene file is not a regular file");
    std::filesystem::remove_all(dir);
}

TEST(InputFile, ADeviceAndAFolderAreRefused) {
    EXPECT_EQ(test::errorOf([&] { readInputFile("/dev/zero", "glTF file"); }),
              "/dev/zero: the glTF file is not a regular file");
    const auto dir = test::tempDir();
    EXPECT_NE(test::errorOf([&] { openInputFile(dir.string(), "image"); }).find("not a regular file"),
              std::string::npos);
    std::filesystem::remove_all(dir);
}

TEST(InputFile, AMissingFileNamesItself) {
    EXPECT_EQ(test::errorOf([&] { readInputFile("/nonexistent/x.bin", "glTF file"); }),
              "/nonexistent/x.bin: cannot open the glTF file (missing or unreadable)");
}

TEST(InputFile, AFileOverTheLimitIsRefusedBeforeReading) {
    const auto dir = test::tempDir();
    std::ofstream(dir / "big.bin", std::ios::binary) << std::string(2000, 'x');
    EXPECT_EQ(test::errorOf([&] { readInputFile((dir / "big.bin").string(), "glTF file", 1000); }),
              (dir / "big.bin").string() + ": the glTF file has 2000 bytes, over the limit of 1000 bytes");
    std::filesystem::remove_all(dir);
}

TEST(InputFolders, AllowWholeComponentsOnlyAndShareOneLogAmongCopies) {
    const InputFolders folders = InputFolders::confinedTo({"/data/scene"});
    EXPECT_TRUE(folders.allows("/data/scene/a.tif"));
    EXPECT_FALSE(folders.allows("/data/scenery/a.tif"));
    EXPECT_FALSE(folders.allows("/etc/passwd"));
    EXPECT_TRUE(InputFolders().allows("/etc/passwd"));
    const InputFolders copy = folders;
    copy.record("/data/scene/m.gltf", "/data/scene/m.bin");
    copy.record("/data/scene/m.gltf", "/data/scene/m.bin");
    EXPECT_EQ(folders.opened(), (std::vector<OpenedInput>{{"/data/scene/m.gltf", "/data/scene/m.bin"}}));
}

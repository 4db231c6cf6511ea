// GDAL's door (io/raster_door.h): every file GDAL opens for a raster, companion files included, is confined to the
// allowed folders, regular, of a companion kind, and logged for the dataset's fingerprint.
#include "io/raster_file.h"

#include "test_files.h"

#include <gdal.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sys/stat.h>

using namespace sward;
using namespace sward::test;

namespace {

namespace fs = std::filesystem;

const char* kGrid = "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 10\n1 2\n";
const char* kAuxXml =
    "<PAMDataset><PAMRasterBand band=\"1\"><NoDataValue>2</NoDataValue></PAMRasterBand></PAMDataset>\n";

// `dir`/scene: the allowed folder, `dir` beside it is outside.
InputFolders sceneFolder(const fs::path& dir) {
    fs::create_directories(dir / "scene");
    return InputFolders::confinedTo({fs::canonical(dir / "scene")});
}

std::vector<std::string> openedPaths(const InputFolders& folders) {
    std::vector<std::string> paths;
    for (const OpenedInput& file : folders.opened()) paths.push_back(file.path);
    return paths;
}

bool contains(const std::vector<std::string>& list, const std::string& item) {
    return std::find(list.begin(), list.end(), item) != list.end();
}

} // namespace

TEST(RasterDoor, CompanionFilesInsideAreReadAndLogged) {
    const fs::path dir = fs::canonical(tempDir());
    const InputFolders folders = sceneFolder(dir);
    const std::string grid = (dir / "scene/dem.asc").string();
    std::ofstream(grid) << kGrid;
    std::ofstream(grid + ".aux.xml") << kAuxXml;
    readRasterBand(grid, {.band = 1, .requireFinite = false, .folders = folders});
    const std::vector<std::string> opened = openedPaths(folders);
    EXPECT_TRUE(contains(opened, grid)) << testing::PrintToString(opened);
    EXPECT_TRUE(contains(opened, grid + ".aux.xml")) << testing::PrintToString(opened);
    for (const OpenedInput& file : folders.opened()) EXPECT_EQ(file.owner, grid);
}

TEST(RasterDoor, AuxXmlSymlinkedOutsideTheFoldersIsRefused) {
    const fs::path dir = fs::canonical(tempDir());
    const InputFolders folders = sceneFolder(dir);
    const std::string grid = (dir / "scene/dem.asc").string();
    std::ofstream(grid) << kGrid;
    std::ofstream(dir / "outside.aux.xml") << kAuxXml;
    fs::create_symlink(dir / "outside.aux.xml", grid + ".aux.xml");
    expectError([&] { readRasterBand(grid, {.band = 1, .requireFinite = false, .folders = folders}); },
                {grid, "dem.asc.aux.xml", (dir / "outside.aux.xml").string(), "outside the scene's folder"});
}

TEST(RasterDoor, FifoCompanionIsRefusedWithoutBlocking) {
    const fs::path dir = fs::canonical(tempDir());
    const InputFolders folders = sceneFolder(dir);
    const std::string grid = (dir / "scene/dem.asc").string();
    std::ofstream(grid) << kGrid;
    ASSERT_EQ(::mkfifo((grid + ".aux.xml").c_str(), 0600), 0);
    expectError([&] { readRasterBand(grid, {.band = 1, .requireFinite = false, .folders = folders}); },
                {"dem.asc.aux.xml", "not a regular file"});
}

TEST(RasterDoor, DevZeroCompanionIsRefusedEvenUnconfined) {
    const fs::path dir = fs::canonical(tempDir());
    const std::string grid = (dir / "dem.asc").string();
    std::ofstream(grid) << kGrid;
    fs::create_symlink("/dev/zero", grid + ".aux.xml");
    expectError([&] { readRasterBand(grid); }, {"dem.asc.aux.xml", "not a regular file"});
}

TEST(RasterDoor, EhdrHeaderInsideIsReadAndOutsideIsRefused) {
    const fs::path dir = fs::canonical(tempDir());
    const InputFolders folders = sceneFolder(dir);
    const std::string raw = (dir / "scene/cover.bil").string();
    std::ofstream(raw, std::ios::binary) << std::string("\x0a\x1e", 2);
    std::ofstream(dir / "scene/cover.hdr") << "ncols 2\nnrows 1\nnbands 1\nnbits 8\nbyteorder I\nlayout bil\n";
    EXPECT_EQ(readRasterBand(raw, {.band = 1, .requireFinite = false, .folders = folders}).values,
              (std::vector<double>{10, 30}));
    fs::rename(dir / "scene/cover.hdr", dir / "cover.hdr");
    fs::create_symlink(dir / "cover.hdr", dir / "scene/cover.hdr");
    expectError([&] { readRasterBand(raw, {.band = 1, .requireFinite = false, .folders = folders}); },
                {"cover.hdr", "outside the scene's folder"});
}

// An HFA .img names its spill file (.ige) in its content; one naming "../o.ige" outside the folders is refused.
TEST(RasterDoor, HfaSpillFileNamedOutsideIsRefused) {
    const fs::path dir = fs::canonical(tempDir());
    const InputFolders folders = sceneFolder(dir);
    GDALAllRegister();
    const char* options[] = {"USE_SPILL=YES", nullptr};
    const std::string made = (dir / "abcd.img").string();
    GDALDatasetH ds =
        GDALCreate(GDALGetDriverByName("HFA"), made.c_str(), 4, 4, 1, GDT_Byte, const_cast<char**>(options));
    ASSERT_NE(ds, nullptr);
    GDALClose(ds);
    ASSERT_TRUE(fs::exists(dir / "abcd.ige"));
    // The .img names "abcd.ige"; the same length "../o.ige" points one folder up.
    std::ifstream in(made, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    const size_t at = bytes.find("abcd.ige");
    ASSERT_NE(at, std::string::npos);
    bytes.replace(at, 8, "../o.ige");
    std::ofstream(dir / "scene/abcd.img", std::ios::binary) << bytes;
    fs::rename(dir / "abcd.ige", dir / "o.ige");
    const std::string img = (dir / "scene/abcd.img").string();
    expectError([&] { readRasterBand(img, {.band = 1, .requireFinite = false, .folders = folders}); },
                {"o.ige", "outside the scene's folder"});
    // Allowed when the folder above is (--allow-assets): then it is logged like any companion.
    const InputFolders wider = InputFolders::confinedTo({dir});
    readRasterBand(img, {.band = 1, .requireFinite = false, .folders = wider});
    EXPECT_TRUE(contains(openedPaths(wider), (dir / "o.ige").string())) << testing::PrintToString(openedPaths(wider));
}

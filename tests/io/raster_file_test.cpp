// Rasters read through GDAL: files written here with GDAL's own API (GTiff, PNG through the MEM driver and
// CreateCopy, an ASCII grid as text), read back value for value, and every refusal as one clear error.
#include "io/raster_file.h"

#include "test_files.h"

#include <gdal.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>

using namespace sward;
using namespace sward::test;

namespace {

struct TiffSpec {
    uint32_t width = 3, height = 2, bands = 1;
    GDALDataType type = GDT_Float32;
    std::vector<double> values;                        // every band: values + band index * 100
    std::optional<std::array<double, 6>> geoTransform; // GDAL order
    std::optional<double> nodata;
    std::vector<std::string> options; // creation options
};

// Writes a GeoTIFF with GDAL's API (the way a GIS writes one).
void writeTiff(const std::string& path, const TiffSpec& s) {
    GDALAllRegister();
    std::vector<const char*> options;
    for (const std::string& o : s.options) options.push_back(o.c_str());
    options.push_back(nullptr);
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), int(s.width), int(s.height), int(s.bands),
                                 s.type, const_cast<char**>(options.data()));
    ASSERT_NE(ds, nullptr);
    if (s.geoTransform) {
        std::array<double, 6> gt = *s.geoTransform;
        GDALSetGeoTransform(ds, gt.data());
    }
    for (uint32_t b = 1; b <= s.bands; ++b) {
        GDALRasterBandH band = GDALGetRasterBand(ds, int(b));
        if (s.nodata) GDALSetRasterNoDataValue(band, *s.nodata);
        if (s.values.empty()) continue;
        std::vector<double> v = s.values;
        for (double& x : v) x += (b - 1) * 100.0;
        EXPECT_EQ(GDALRasterIO(band, GF_Write, 0, 0, int(s.width), int(s.height), v.data(), int(s.width), int(s.height),
                               GDT_Float64, 0, 0),
                  CE_None);
    }
    GDALClose(ds);
}

// A file of another format made from an in-memory raster (MEM driver + CreateCopy).
void writeCopy(const std::string& driver, const std::string& path, uint32_t width, uint32_t height, GDALDataType type,
               std::vector<double> values) {
    GDALAllRegister();
    GDALDatasetH mem = GDALCreate(GDALGetDriverByName("MEM"), "", int(width), int(height), 1, type, nullptr);
    ASSERT_NE(mem, nullptr);
    EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(mem, 1), GF_Write, 0, 0, int(width), int(height), values.data(),
                           int(width), int(height), GDT_Float64, 0, 0),
              CE_None);
    GDALDatasetH copy =
        GDALCreateCopy(GDALGetDriverByName(driver.c_str()), path.c_str(), mem, FALSE, nullptr, nullptr, nullptr);
    ASSERT_NE(copy, nullptr);
    GDALClose(copy);
    GDALClose(mem);
}

const std::array<double, 6> kUtm = {500000.0, 10.0, 0.0, 4100000.0, 0.0, -10.0};

} // namespace

TEST(RasterFile, GeoTiffValuesNodataAndGeoTransformReadBack) {
    const std::string path = (tempDir() / "cover.tif").string();
    writeTiff(path, {.values = {10, 20, 30, 40, -9999, 95.5}, .geoTransform = kUtm, .nodata = -9999.0});
    const RasterBand r = readRasterBand(path);
    EXPECT_EQ(r.width, 3u);
    EXPECT_EQ(r.height, 2u);
    EXPECT_EQ(r.values, (std::vector<double>{10, 20, 30, 40, -9999, 95.5})); // top row first
    EXPECT_EQ(r.at(2, 1), 95.5);
    ASSERT_TRUE(r.nodata);
    EXPECT_EQ(*r.nodata, -9999.0);
    EXPECT_TRUE(r.isNodata(r.at(1, 1)));
    EXPECT_FALSE(r.isNodata(r.at(0, 0)));
    ASSERT_TRUE(r.geoTransform);
    EXPECT_EQ(r.geoTransform->originX, 500000.0);
    EXPECT_EQ(r.geoTransform->originY, 4100000.0);
    EXPECT_EQ(r.geoTransform->pixelWidth, 10.0);
    EXPECT_EQ(r.geoTransform->pixelHeight, 10.0);
    EXPECT_EQ(r.source, path);
}

TEST(RasterFile, ReadsTheBandAskedFor) {
    const std::string path = (tempDir() / "bands.tif").string();
    writeTiff(path, {.bands = 3, .values = {1, 2, 3, 4, 5, 6}});
    EXPECT_EQ(readRasterBand(path, {.band = 3}).values, (std::vector<double>{201, 202, 203, 204, 205, 206}));
    EXPECT_FALSE(readRasterBand(path).nodata);
}

TEST(RasterFile, LargeIntegerCodesAreExact) {
    const std::string path = (tempDir() / "codes.tif").string();
    writeTiff(path, {.width = 2, .height = 1, .type = GDT_UInt32, .values = {4294967295.0, 16777217.0}});
    EXPECT_EQ(readRasterBand(path).values, (std::vector<double>{4294967295.0, 16777217.0})); // 2^24 + 1: not a float
}

TEST(RasterFile, SixteenBitPngWithoutGeoreferencing) {
    const std::string path = (tempDir() / "heights.png").string();
    writeCopy("PNG", path, 2, 2, GDT_UInt16, {0, 1000, 65535, 7});
    const RasterBand r = readRasterBand(path);
    EXPECT_EQ(r.values, (std::vector<double>{0, 1000, 65535, 7})); // raw samples, not normalised
    EXPECT_FALSE(r.geoTransform);
    EXPECT_FALSE(r.nodata);
}

TEST(RasterFile, EightBitGreyPngHoldsClassCodes) {
    const auto path = tempDir() / "codes.png";
    writePng(path, 2, 1, 1, 8, {10.0f / 255.0f, 30.0f / 255.0f});
    EXPECT_EQ(readRasterBand(path.string()).values, (std::vector<double>{10, 30}));
}

TEST(RasterFile, AsciiGridWithNodataAndCorner) {
    const auto path = tempDir() / "grid.asc";
    std::ofstream(path) << "ncols 2\nnrows 2\nxllcorner 100\nyllcorner 200\ncellsize 5\nNODATA_value -1\n"
                           "1.5 -1\n3 4\n";
    const RasterBand r = readRasterBand(path.string());
    EXPECT_EQ(r.values, (std::vector<double>{1.5, -1, 3, 4}));
    EXPECT_EQ(r.nodata, -1.0);
    ASSERT_TRUE(r.geoTransform);
    EXPECT_EQ(r.geoTransform->originX, 100.0);
    EXPECT_EQ(r.geoTransform->originY, 210.0); // lower-left corner + 2 rows of 5 m
}

TEST(RasterFile, NanNodataIsNotANonFiniteValue) {
    const std::string path = (tempDir() / "nan.tif").string();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    writeTiff(path, {.width = 2, .height = 1, .values = {nan, 1.0}, .nodata = nan});
    const RasterBand r = readRasterBand(path, {.requireFinite = true});
    EXPECT_TRUE(r.isNodata(r.at(0, 0)));
    EXPECT_EQ(r.at(1, 0), 1.0);
}

TEST(RasterFile, GdalPrintsNothing) {
    const auto dir = tempDir();
    std::ofstream(dir / "text.tif") << "not a tiff\n";
    ::testing::internal::CaptureStderr();
    EXPECT_NE(errorOf([&] { readRasterBand((dir / "text.tif").string()); }), "");
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST(RasterFileErrors, MissingFileNamesTheFile) {
    const std::string path = (tempDir() / "absent.tif").string();
    expectError([&] { readRasterBand(path); }, {path, "missing"});
}

TEST(RasterFileErrors, FolderIsNotARegularFile) {
    const std::string path = tempDir().string();
    expectError([&] { readRasterBand(path); }, {path, "not a regular file"});
}

TEST(RasterFileErrors, VirtualFileSystemsAreRefusedBeforeGdal) {
    for (const std::string path :
         {"/vsicurl/https://example.com/cover.tif", "/VSIS3/bucket/cover.tif", "/vsimem/cover.tif"})
        expectError([&] { readRasterBand(path); }, {path, "/vsi", "local file"});
}

TEST(RasterFileErrors, TextIsNotARasterAndGdalSaysWhy) {
    const auto path = tempDir() / "notes.tif";
    std::ofstream(path) << "hello\n";
    expectError([&] { readRasterBand(path.string()); }, {path.string(), "not a raster file", "GTiff", "GDAL: "});
}

TEST(RasterFileErrors, TruncatedGeoTiffNamesTheFile) {
    const auto path = tempDir() / "cut.tif";
    writeTiff(
        path.string(),
        {.width = 64, .height = 64, .values = std::vector<double>(64 * 64, 7.0), .options = {"COMPRESS=DEFLATE"}});
    std::filesystem::resize_file(path, std::filesystem::file_size(path) - 40);
    const std::string message = errorOf([&] { readRasterBand(path.string()); });
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
}

TEST(RasterFileErrors, BandOutOfRangeSaysHowManyThereAre) {
    const std::string path = (tempDir() / "two.tif").string();
    writeTiff(path, {.bands = 2, .values = {1, 2, 3, 4, 5, 6}});
    expectError([&] { readRasterBand(path, {.band = 3}); }, {path, "2 band(s)", "band 3 does not exist"});
    expectError([&] { readRasterBand(path, {.band = 0}); }, {path, "band 0 does not exist", "from 1"});
}

TEST(RasterFileErrors, RotatedGeoTransformIsRefused) {
    const std::string path = (tempDir() / "rotated.tif").string();
    writeTiff(path, {.values = {1, 2, 3, 4, 5, 6}, .geoTransform = std::array<double, 6>{0, 10, 2, 0, 2, -10}});
    expectError([&] { readRasterBand(path); }, {path, "rotated or sheared", "north-up"});
}

TEST(RasterFileErrors, SouthUpGeoTransformIsRefused) {
    const std::string path = (tempDir() / "south.tif").string();
    writeTiff(path, {.values = {1, 2, 3, 4, 5, 6}, .geoTransform = std::array<double, 6>{0, 10, 0, 0, 0, 10}});
    expectError([&] { readRasterBand(path); }, {path, "not north up"});
}

TEST(RasterFileErrors, EdgeOverTheLimitIsRefusedBeforeReading) {
    const std::string path = (tempDir() / "wide.tif").string();
    writeTiff(path, {.width = kMaxRasterEdge + 1, .height = 1, .type = GDT_Byte, .options = {"SPARSE_OK=TRUE"}});
    expectError([&] { readRasterBand(path); }, {path, "32769x1", "each edge must be 1..32768"});
}

TEST(RasterFileErrors, PixelCountOverTheLimitIsRefusedBeforeReading) {
    // 16384x16384: a 1.2 MB GeoTIFF that took 3.4 GB as a heightmap and 8.3 GB then std::bad_alloc as a land cover.
    const std::string path = (tempDir() / "huge.tif").string();
    writeTiff(path, {.width = 16384, .height = 16384, .type = GDT_Byte, .options = {"SPARSE_OK=TRUE"}});
    expectError([&] { readRasterBand(path); },
                {path, "16384x16384: 268435456 pixels, over the limit of 67108864 (8192x8192)"});
}

TEST(RasterFileErrors, NonFiniteValueNamesThePixelWhenFiniteIsRequired) {
    const std::string path = (tempDir() / "inf.tif").string();
    writeTiff(path, {.values = {0, 1, 2, 3, std::numeric_limits<double>::infinity(), 5}, .nodata = -1.0});
    EXPECT_TRUE(std::isinf(readRasterBand(path).at(1, 1)));
    expectError([&] { readRasterBand(path, {.requireFinite = true}); }, {path, "inf", "pixel (1, 1)"});
}

// Windows: readRasterInfo describes the raster, readRasterWindow reads part of it, sample for sample.
namespace {

// A 7x5 raster whose value names its pixel: 10 * column + row.
std::string writeNumbered(const std::string& name) {
    const std::string path = (tempDir() / name).string();
    std::vector<double> values;
    for (uint32_t row = 0; row < 5; ++row)
        for (uint32_t column = 0; column < 7; ++column) values.push_back(10.0 * column + row);
    writeTiff(path, {.width = 7, .height = 5, .values = values, .geoTransform = kUtm, .nodata = -1.0});
    return path;
}

} // namespace

TEST(RasterWindow, InfoIsTheHeaderWithoutPixels) {
    const std::string path = writeNumbered("info.tif");
    const RasterInfo info = readRasterInfo(path);
    EXPECT_EQ(info.width, 7u);
    EXPECT_EQ(info.height, 5u);
    EXPECT_EQ(info.nodata, -1.0);
    ASSERT_TRUE(info.geoTransform);
    EXPECT_EQ(info.geoTransform->originX, 500000.0);
    EXPECT_EQ(info.source, path);
}

TEST(RasterWindow, WindowHoldsTheSamplesOfTheWholeBand) {
    const std::string path = writeNumbered("window.tif");
    const RasterBand whole = readRasterBand(path);
    const RasterBand w = readRasterWindow(path, {.column = 2, .row = 1, .width = 4, .height = 3});
    ASSERT_EQ(w.width, 4u);
    ASSERT_EQ(w.height, 3u);
    for (uint32_t j = 0; j < 3; ++j)
        for (uint32_t i = 0; i < 4; ++i) EXPECT_EQ(w.at(i, j), whole.at(2 + i, 1 + j)) << i << ", " << j;
    EXPECT_EQ(w.nodata, -1.0);
    ASSERT_TRUE(w.geoTransform);
    EXPECT_EQ(w.geoTransform->originX, 500020.0); // the window's top-left corner
    EXPECT_EQ(w.geoTransform->originY, 4099990.0);
    EXPECT_EQ(w.geoTransform->pixelWidth, 10.0);
}

TEST(RasterWindow, StepPicksEveryStepthSampleExactly) {
    const std::string path = writeNumbered("step.tif");
    const RasterBand w = readRasterWindow(path, {.column = 0, .row = 1, .width = 3, .height = 2, .step = 3});
    EXPECT_EQ(w.values, (std::vector<double>{1, 31, 61, 4, 34, 64})); // columns 0, 3, 6; rows 1, 4
    ASSERT_TRUE(w.geoTransform);
    // Sample (1, 1) is the file's (3, 4): its centre at 500000 + 3.5 * 10 east, 4100000 - 4.5 * 10 north.
    EXPECT_EQ(w.geoTransform->originX + 1.5 * w.geoTransform->pixelWidth, 500035.0);
    EXPECT_EQ(w.geoTransform->originY - 1.5 * w.geoTransform->pixelHeight, 4099955.0);
}

TEST(RasterWindow, WindowOfARasterFarLargerThanTheReadLimit) {
    // 20,000 x 20,000 Float32 (1.6 GB as doubles), sparse: only the block at (256..511, 512..767) is written.
    const std::string path = (tempDir() / "sparse-dem.tif").string();
    writeTiff(path, {.width = 20000, .height = 20000, .options = {"SPARSE_OK=TRUE", "TILED=YES"}});
    GDALDatasetH ds = GDALOpen(path.c_str(), GA_Update);
    ASSERT_NE(ds, nullptr);
    std::vector<double> block(256 * 256, 7.5);
    ASSERT_EQ(
        GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 256, 512, 256, 256, block.data(), 256, 256, GDT_Float64, 0, 0),
        CE_None);
    GDALClose(ds);
    EXPECT_LT(std::filesystem::file_size(path), 4u << 20);
    EXPECT_EQ(readRasterInfo(path).width, 20000u);
    const RasterBand w = readRasterWindow(path, {.column = 250, .row = 510, .width = 10, .height = 4});
    EXPECT_EQ(w.at(0, 0), 0.0); // an unwritten block reads as zeros
    EXPECT_EQ(w.at(6, 2), 7.5);
    const RasterBand far = readRasterWindow(path, {.column = 0, .row = 0, .width = 200, .height = 200, .step = 100});
    EXPECT_EQ(far.at(3, 6), 7.5); // the file's (300, 600)
    expectError([&] { readRasterBand(path); }, {path, "20000x20000", "over the limit"});
    expectError([&] { readRasterWindow(path, {.width = 9000, .height = 9000}); },
                {path, "window of 9000x9000 samples", "over the limit"});
}

TEST(RasterWindowErrors, WindowBeyondTheRasterOrEmptyNamesTheWindow) {
    const std::string path = writeNumbered("beyond.tif");
    expectError([&] { readRasterWindow(path, {.column = 5, .row = 0, .width = 3, .height = 1}); },
                {path, "window of 3x1 samples at column 5, row 0", "reaches beyond its 7x5 samples"});
    expectError([&] { readRasterWindow(path, {.column = 0, .row = 0, .width = 3, .height = 3, .step = 3}); },
                {path, "every 3 samples", "reaches beyond"});
    expectError([&] { readRasterWindow(path, {.width = 0, .height = 1}); }, {path, "is empty"});
}

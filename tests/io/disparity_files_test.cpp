// PFM, KITTI PNG and Middlebury calib.txt: round trips, the exact byte layout, quantisation and clear errors.
#include "io/disparity_files.h"
#include "test_files.h"

#include "common/error.h"
#include "common/hash.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

using namespace sward;
namespace {

// io tests use the io layer's helpers only (stereo_test_files.h builds on dataset/).
std::string tempDir() {
    return sward::test::tempDir().string();
}

std::string readFile(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

std::vector<float> sampleDisparity(uint32_t w, uint32_t h) {
    std::vector<float> d(size_t(w) * h);
    HashStream stream{hashKey({42})};
    for (float& v : d) v = stream.nextFloat() * 200.0f;
    d[0] = 0.0f;     // invalid
    d[5] = INFINITY; // invalid in another encoding
    d[w + 1] = 255.99f;
    return d;
}

} // namespace

TEST(DisparityFiles, PfmRoundTripsExactlyAndKeepsInvalidPixels) {
    const uint32_t w = 7, h = 5;
    std::vector<float> d = sampleDisparity(w, h);
    const std::string path = tempDir() + "/d.pfm";
    writePfm(path, w, h, d);
    DisparityMap back = readPfm(path);
    ASSERT_EQ(back.width, w);
    ASSERT_EQ(back.height, h);
    for (size_t i = 0; i < d.size(); ++i) {
        if (isValidDisparity(d[i]))
            EXPECT_EQ(back.values[i], d[i]) << i;
        else
            EXPECT_EQ(back.values[i], 0.0f) << i;
    }
    EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

TEST(DisparityFiles, PfmLayoutIsLittleEndianBottomRowFirstWithInfForInvalid) {
    const std::vector<float> d = {1, 2, 0, // top row; 0 = invalid
                                  4, 5, 6};
    const std::string path = tempDir() + "/d.pfm";
    writePfm(path, 3, 2, d);
    const std::string bytes = readFile(path);
    const std::string header = "Pf\n3 2\n-1\n";
    ASSERT_EQ(bytes.size(), header.size() + 6 * 4);
    EXPECT_EQ(bytes.substr(0, header.size()), header);
    auto value = [&](size_t k) {
        uint8_t b[4];
        std::memcpy(b, bytes.data() + header.size() + 4 * k, 4);
        return std::bit_cast<float>(uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24);
    };
    EXPECT_EQ(value(0), 4.0f); // the bottom row comes first
    EXPECT_EQ(value(2), 6.0f);
    EXPECT_EQ(value(3), 1.0f);
    EXPECT_TRUE(std::isinf(value(5)) && value(5) > 0);
}

TEST(DisparityFiles, ReadsBigEndianPfm) {
    std::string bytes = "Pf\n2 1\n1.0\n";
    for (float v : {3.5f, 7.25f}) {
        uint32_t bits = std::bit_cast<uint32_t>(v);
        for (int shift = 24; shift >= 0; shift -= 8) bytes.push_back(char((bits >> shift) & 0xff));
    }
    const std::string path = tempDir() + "/be.pfm";
    std::ofstream(path, std::ios::binary) << bytes;
    DisparityMap map = readPfm(path);
    EXPECT_EQ(map.values, (std::vector<float>{3.5f, 7.25f}));
}

TEST(DisparityFiles, BadPfmFilesAreOneClearError) {
    const std::string dir = tempDir();
    std::ofstream(dir + "/short.pfm", std::ios::binary) << "Pf\n4 4\n-1\n" << std::string(20, '\0');
    std::ofstream(dir + "/colour.pfm", std::ios::binary) << "PF\n1 1\n-1\n" << std::string(12, '\0');
    std::ofstream(dir + "/text.pfm", std::ios::binary) << "hello";
    for (const char* name : {"/short.pfm", "/colour.pfm", "/text.pfm", "/missing.pfm"}) {
        try {
            readPfm(dir + name);
            ADD_FAILURE() << name << " was accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(name + 1), std::string::npos) << e.what();
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        }
    }
}

TEST(DisparityFiles, KittiPngRoundTripsWithin1Over512Pixel) {
    const uint32_t w = 9, h = 4;
    std::vector<float> d = sampleDisparity(w, h);
    d[7] = 300.0f;      // 300 * 256 > 65535: KITTI cannot store it, so it becomes invalid
    d[8] = 0.001f;      // rounds to 0, which KITTI reads as invalid
    d[9] = 12.0f / 256; // exactly representable
    const std::string path = tempDir() + "/d.png";
    writeKittiPng(path, w, h, d);
    cv::Mat raw = cv::imread(path, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(raw.type(), CV_16UC1);
    EXPECT_EQ(raw.at<uint16_t>(0, 1), uint16_t(std::lround(d[1] * 256.0)));
    DisparityMap back = readKittiPng(path);
    ASSERT_EQ(back.width, w);
    ASSERT_EQ(back.height, h);
    for (size_t i = 0; i < d.size(); ++i) {
        if (i == 7 || i == 8 || !isValidDisparity(d[i])) {
            EXPECT_EQ(back.values[i], 0.0f) << i;
            continue;
        }
        EXPECT_LE(std::abs(back.values[i] - d[i]), 0.5f / 256.0f + 1e-6f) << i; // the quantisation bound
    }
    EXPECT_EQ(back.values[9], 12.0f / 256);
    EXPECT_EQ(readDisparity(path).values, back.values);
}

TEST(DisparityFiles, KittiReaderRefusesEightBitPng) {
    const std::string path = tempDir() + "/eight.png";
    cv::imwrite(path, cv::Mat(2, 2, CV_8UC1, cv::Scalar(3)));
    EXPECT_THROW(readKittiPng(path), Error);
    EXPECT_THROW(readDisparity(tempDir() + "/d.tiff"), Error);
}

TEST(DisparityFiles, MiddleburyCalibRoundTrips) {
    StereoCalib c;
    c.cam0 = {1733.74, 0, 792.27, 0, 1733.74, 541.89, 0, 0, 1};
    c.cam1 = {1733.74, 0, 792.27, 0, 1733.74, 541.89, 0, 0, 1};
    c.doffs = 0;
    c.baselineMm = 536.62;
    c.width = 1920;
    c.height = 1080;
    c.ndisp = 176;
    c.vmin = 55;
    c.vmax = 142;
    const std::string path = tempDir() + "/calib.txt";
    writeMiddleburyCalib(path, c);
    const std::string text = readFile(path);
    EXPECT_NE(text.find("cam0=[1733.74 0 792.27; 0 1733.74 541.89; 0 0 1]\n"), std::string::npos) << text;
    EXPECT_NE(text.find("baseline=536.62\n"), std::string::npos) << text;
    StereoCalib back = readMiddleburyCalib(path);
    EXPECT_EQ(back.cam0, c.cam0);
    EXPECT_EQ(back.cam1, c.cam1);
    EXPECT_EQ(back.baselineMm, c.baselineMm);
    EXPECT_EQ(back.width, c.width);
    EXPECT_EQ(back.height, c.height);
    EXPECT_EQ(back.ndisp, c.ndisp);
    EXPECT_EQ(back.vmin, c.vmin);
    EXPECT_EQ(back.vmax, c.vmax);
    EXPECT_NEAR(back.depthMetres(100.0), 536.62 * 1733.74 / 100.0 * 1e-3, 1e-12);
}

TEST(DisparityFiles, ReadsAMiddlebury2014CalibFile) {
    // The layout of Middlebury 2014's Adirondack calib.txt, with its extra keys and CRLF line ends.
    const std::string path = tempDir() + "/calib.txt";
    std::ofstream(path) << "cam0=[4161.221 0 1445.577; 0 4161.221 984.686; 0 0 1]\r\n"
                           "cam1=[4161.221 0 1654.636; 0 4161.221 984.686; 0 0 1]\r\n"
                           "doffs=209.059\r\nbaseline=176.252\r\nwidth=2880\r\nheight=1988\r\nndisp=280\r\n"
                           "isint=0\r\nvmin=33\r\nvmax=218\r\ndyavg=0\r\ndymax=0\r\n";
    StereoCalib c = readMiddleburyCalib(path);
    EXPECT_EQ(c.cam1[2], 1654.636);
    EXPECT_EQ(c.doffs, 209.059);
    EXPECT_EQ(c.ndisp, 280u);
    EXPECT_EQ(c.width, 2880u);
}

TEST(DisparityFiles, CalibErrorsNameTheFileAndKey) {
    const std::string path = tempDir() + "/calib.txt";
    std::ofstream(path) << "cam0=[1 0 0; 0 1 0; 0 0 1]\ncam1=[1 0 0; 0 1 0; 0 0 1]\nbaseline=abc\nwidth=4\nheight=4\n"
                           "ndisp=16\n";
    try {
        readMiddleburyCalib(path);
        FAIL() << "accepted a bad baseline";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("baseline"), std::string::npos) << e.what();
    }
    std::ofstream(path) << "cam0=[1 0 0; 0 1 0; 0 0 1]\n";
    EXPECT_THROW(readMiddleburyCalib(path), Error);
}

// Middlebury .flo and KITTI flow PNG: round trips, the exact byte layout, quantisation and clear errors for
// corrupt files (never reading past the data, never allocating what a header claims before checking the file).
#include "io/flow_files.h"
#include "test_files.h"

#include "common/error.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>

using namespace sward;
namespace {

std::string tempDir() {
    return sward::test::tempDir().string();
}

std::string readFile(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

// Little-endian bytes written by hand, independent of the code under test.
void putLittle(std::string& bytes, uint32_t bits) {
    for (int shift = 0; shift < 32; shift += 8) bytes.push_back(char((bits >> shift) & 0xff));
}
void putFloat(std::string& bytes, float v) {
    putLittle(bytes, std::bit_cast<uint32_t>(v));
}

// A 3x2 field: a few exact values, a non-representable one, and an invalid pixel.
FlowField sampleFlow() {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    return {3,
            2,
            {1.5f, -0.25f, 0.1f, 7.0f, nan, nan, // top row
             -12.75f, 3.0f, 100.0f, -200.5f, 0.0f, 0.0f}};
}

void expectSameFlow(const FlowField& a, const FlowField& b) {
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    ASSERT_EQ(a.uv.size(), b.uv.size());
    for (size_t i = 0; i < a.uv.size(); ++i) {
        if (std::isnan(a.uv[i]))
            EXPECT_TRUE(std::isnan(b.uv[i])) << i;
        else
            EXPECT_EQ(a.uv[i], b.uv[i]) << i;
    }
}

void expectError(const std::function<void()>& read, const std::string& file, const std::string& problem) {
    try {
        read();
        ADD_FAILURE() << file << " was accepted";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(file), std::string::npos) << message;
        EXPECT_NE(message.find(problem), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

} // namespace

TEST(FlowFiles, FloRoundTripsExactlyAndKeepsInvalidPixels) {
    const std::string path = tempDir() + "/f.flo";
    writeFlo(path, sampleFlow());
    expectSameFlow(sampleFlow(), readFlo(path));
    EXPECT_EQ(readFlow(path).width, 3u);
}

TEST(FlowFiles, FloLayoutIsTagWidthHeightThenLittleEndianPairsTopRowFirst) {
    const std::string path = tempDir() + "/f.flo";
    writeFlo(path, sampleFlow());
    std::string expected;
    expected += "PIEH"; // the tag 202021.25f, little-endian
    putLittle(expected, 3);
    putLittle(expected, 2);
    for (float v : {1.5f, -0.25f, 0.1f, 7.0f, 1e10f, 1e10f, -12.75f, 3.0f, 100.0f, -200.5f, 0.0f, 0.0f})
        putFloat(expected, v);
    EXPECT_TRUE(readFile(path) == expected) << "the .flo bytes differ from Middlebury's layout";
}

TEST(FlowFiles, HandWrittenFloReadsWithUnknownAndInfiniteAsInvalid) {
    std::string bytes = "PIEH";
    putLittle(bytes, 2);
    putLittle(bytes, 1);
    for (float v : {-3.25f, 1e10f, INFINITY, 2.0f}) putFloat(bytes, v); // one unknown u, one infinite u
    const std::string path = tempDir() + "/hand.flo";
    std::ofstream(path, std::ios::binary) << bytes;
    const FlowField flow = readFlo(path);
    ASSERT_EQ(flow.uv.size(), 4u);
    EXPECT_TRUE(std::isnan(flow.u(0)) && std::isnan(flow.v(0))) << "a vector with one unknown component is unknown";
    EXPECT_TRUE(std::isnan(flow.u(1)) && std::isnan(flow.v(1)));
}

TEST(FlowFiles, KittiPngRoundTripsWithin1Over128PixelAndStoresChannelsRgb) {
    const std::string path = tempDir() + "/f.png";
    FlowField flow = sampleFlow();
    flow.uv[8] = 600.0f; // 600 * 64 + 32768 > 65535: KITTI cannot hold it, the pixel becomes invalid
    writeKittiFlowPng(path, flow);
    cv::Mat raw = cv::imread(path, cv::IMREAD_UNCHANGED); // BGR: file channels R, G, B reversed
    ASSERT_EQ(raw.type(), CV_16UC3);
    EXPECT_EQ(raw.at<cv::Vec3w>(0, 0), cv::Vec3w(1, 32768 - 16, 32768 + 96)); // u 1.5, v -0.25, valid
    EXPECT_EQ(raw.at<cv::Vec3w>(0, 2), cv::Vec3w(0, 0, 0));                   // invalid
    const FlowField back = readKittiFlowPng(path);
    ASSERT_EQ(back.width, 3u);
    for (size_t i : {0u, 1u, 3u, 5u}) {
        EXPECT_NEAR(back.u(i), flow.u(i), 1.0 / 128) << i;
        EXPECT_NEAR(back.v(i), flow.v(i), 1.0 / 128) << i;
    }
    EXPECT_EQ(back.u(0), 1.5f); // multiples of 1/64 are exact
    EXPECT_TRUE(std::isnan(back.u(2)) && std::isnan(back.u(4)));
    EXPECT_EQ(readFlow(path).width, 3u);
}

TEST(FlowFiles, HandWrittenKittiPngIsDecoded) {
    cv::Mat raw(1, 2, CV_16UC3);
    raw.at<cv::Vec3w>(0, 0) = {1, 32768 + 64, 32768 - 128}; // B valid, G = v = 1, R = u = -2
    raw.at<cv::Vec3w>(0, 1) = {0, 40000, 40000};            // invalid whatever u and v say
    const std::string path = tempDir() + "/hand.png";
    ASSERT_TRUE(cv::imwrite(path, raw));
    const FlowField flow = readKittiFlowPng(path);
    EXPECT_EQ(flow.u(0), -2.0f);
    EXPECT_EQ(flow.v(0), 1.0f);
    EXPECT_TRUE(std::isnan(flow.u(1)));
}

TEST(FlowFiles, CorruptFloFilesAreOneClearErrorEach) {
    const std::string dir = tempDir();
    auto write = [&](const std::string& name, const std::string& bytes) {
        std::ofstream(dir + "/" + name, std::ios::binary) << bytes;
        return dir + "/" + name;
    };
    std::string header = "PIEH";
    putLittle(header, 4);
    putLittle(header, 4);
    std::string badTag = "PIEX" + header.substr(4) + std::string(128, '\0');
    std::string absurd = "PIEH";
    putLittle(absurd, 1u << 30); // 2^30 x 2^30: must be refused before anything that size is allocated
    putLittle(absurd, 1u << 30);
    std::string negative = "PIEH";
    putLittle(negative, uint32_t(-5));
    putLittle(negative, 4);
    std::string zero = "PIEH";
    putLittle(zero, 0);
    putLittle(zero, 4);
    const struct {
        std::string path, problem;
    } cases[] = {
        {write("tag.flo", badTag), "tag"},
        {write("short.flo", header + std::string(8 * 4 * 4 - 1, '\0')), "truncated"},
        {write("header.flo", "PIEH\4"), "truncated"},
        {write("long.flo", header + std::string(8 * 4 * 4 + 8, '\0')), "after"},
        {write("absurd.flo", absurd + std::string(64, '\0')), "out of range"},
        {write("negative.flo", negative), "out of range"},
        {write("zero.flo", zero), "out of range"},
        {write("empty.flo", ""), "truncated"},
        {dir + "/missing.flo", "no such file"},
    };
    for (const auto& c : cases) expectError([&] { readFlo(c.path); }, c.path, c.problem);
    expectError([&] { readFlow(dir + "/f.pfm"); }, "f.pfm", "unknown flow format");
    cv::Mat grey(2, 2, CV_16UC1, cv::Scalar(0));
    ASSERT_TRUE(cv::imwrite(dir + "/grey.png", grey));
    expectError([&] { readKittiFlowPng(dir + "/grey.png"); }, "grey.png", "3 channels");
}

TEST(FlowFiles, WritersRefuseAFieldOfTheWrongSize) {
    FlowField flow = sampleFlow();
    flow.uv.pop_back();
    EXPECT_THROW(writeFlo(tempDir() + "/f.flo", flow), Error);
    EXPECT_THROW(writeKittiFlowPng(tempDir() + "/f.png", flow), Error);
}

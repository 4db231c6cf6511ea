// Image files: EXR written by sward read back with OpenCV.
#include "common/half_float.h"
#include "common/hash.h"
#include "io/image_files.h"
#include "io/image_io.h"

#include "test_files.h"

#include <opencv2/imgcodecs.hpp>

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

using namespace sward;

TEST(ExrFiles, ReadBackWithOpenCvToExactlyTheWrittenValues) {
    const std::string dir = sward::test::tempDir().string();
    const uint32_t w = 7, h = 5;
    std::vector<float> depth(w * h);
    std::vector<uint16_t> rgba(w * h * 4);
    for (uint32_t i = 0; i < w * h; ++i) {
        depth[i] = i == 3 ? INFINITY : 0.001f + float(i) * 1.37f;
        for (uint32_t c = 0; c < 4; ++c) rgba[i * 4 + c] = uint16_t(0x3000 + i * 37 + c * 5); // assorted halves
    }
    writeExrDepth(dir + "/d.exr", w, h, depth);
    writeExrRgbaHalf(dir + "/c.exr", w, h, rgba);
    cv::Mat d = cv::imread(dir + "/d.exr", cv::IMREAD_UNCHANGED);
    cv::Mat c = cv::imread(dir + "/c.exr", cv::IMREAD_UNCHANGED);
    ASSERT_EQ(d.type(), CV_32FC1);
    ASSERT_EQ(c.type(), CV_32FC4);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            uint32_t i = y * w + x;
            EXPECT_EQ(d.at<float>(int(y), int(x)), depth[i]);
            cv::Vec4f px = c.at<cv::Vec4f>(int(y), int(x));
            EXPECT_EQ(px[2], halfBitsToFloat(rgba[i * 4 + 0])); // R (OpenCV orders BGRA)
            EXPECT_EQ(px[1], halfBitsToFloat(rgba[i * 4 + 1])); // G
            EXPECT_EQ(px[0], halfBitsToFloat(rgba[i * 4 + 2])); // B
            EXPECT_EQ(px[3], halfBitsToFloat(rgba[i * 4 + 3])); // A
        }
    EXPECT_FALSE(std::filesystem::exists(dir + "/d.exr.tmp"));
}

TEST(ExrFiles, FloatSamplesReadBackThroughLoadImageExactly) {
    const std::string dir = sward::test::tempDir().string();
    for (uint32_t channels : {1u, 3u, 4u}) {
        const uint32_t w = 3, h = 2;
        std::vector<float> samples(w * h * channels);
        for (size_t i = 0; i < samples.size(); ++i) samples[i] = float(i) * 0.75f - 2.0f;
        const std::string path = dir + "/f" + std::to_string(channels) + ".exr";
        writeExr(path, w, h, channels, samples);
        const ImageData image = loadImage(path);
        EXPECT_EQ(image.channels, channels);
        EXPECT_EQ(image.samples, samples) << channels << " channel(s)";
        EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
    }
}

namespace {
std::vector<char> readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void writeAll(const std::string& path, const std::vector<char>& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}
} // namespace

TEST(ExrFiles, ImagesOfSeveralStripsReadBackExactly) {
    // 1100 floats a row: loadImage reads 238 rows at a time, so 300 rows take two strips.
    const std::string path = sward::test::tempDir().string() + "/wide.exr";
    const uint32_t w = 1100, h = 300;
    std::vector<float> samples(w * h);
    for (size_t i = 0; i < samples.size(); ++i) samples[i] = float(i % 9973) * 0.5f;
    writeExr(path, w, h, 1, samples);
    EXPECT_EQ(loadImage(path).samples, samples);
}

TEST(ExrFiles, AnAttributeLargerThanTheFileIsRefusedBeforeOpenExrAllocatesIt) {
    const std::string path = sward::test::tempDir().string() + "/big-attribute.exr";
    writeExr(path, 2, 2, 1, std::vector<float>(4, 1.0f));
    std::vector<char> bytes = readAll(path);
    const std::string key("channels\0chlist\0", 16);
    const auto at = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
    ASSERT_NE(at, bytes.end());
    const uint32_t huge = 0x7fff0000u; // about 2 GiB: OpenEXR would allocate it, then find the file ends
    std::memcpy(&*(at + 16), &huge, 4);
    writeAll(path, bytes);
    sward::test::expectError([&] { loadImage(path); }, {path, "an attribute claims 2147418112 bytes"});
}

// writePng8 / writePng16 take channels in the file's order (RGB, RGBA): each sample must come back in its channel,
// through sward's reader and through OpenCV's as a user reads it.
TEST(PngFiles, EightAndSixteenBitSamplesReadBackExactlyInTheirChannels) {
    const std::string dir = sward::test::tempDir().string();
    const uint32_t w = 5, h = 3;
    for (uint32_t bits : {8u, 16u})
        for (uint32_t channels : {1u, 3u, 4u}) {
            const std::string path = dir + "/p" + std::to_string(bits) + "-" + std::to_string(channels) + ".png";
            const uint32_t maxValue = bits == 8 ? 255u : 65535u;
            std::vector<uint32_t> values(size_t(w) * h * channels);
            for (size_t i = 0; i < values.size(); ++i)
                values[i] = uint32_t(i * 7919u + 13u * (i % channels)) % (maxValue + 1);
            if (bits == 8)
                writePng8(path, w, h, channels, std::vector<uint8_t>(values.begin(), values.end()));
            else
                writePng16(path, w, h, channels, std::vector<uint16_t>(values.begin(), values.end()));
            EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));

            const ImageData image = loadImage(path);
            ASSERT_EQ(image.bitDepth, bits);
            ASSERT_EQ(image.channels, channels);
            const cv::Mat cvImage = cv::imread(path, cv::IMREAD_UNCHANGED);
            ASSERT_EQ(cvImage.depth(), bits == 8 ? CV_8U : CV_16U);
            ASSERT_EQ(uint32_t(cvImage.channels()), channels);
            for (uint32_t y = 0; y < h; ++y)
                for (uint32_t x = 0; x < w; ++x)
                    for (uint32_t c = 0; c < channels; ++c) {
                        const uint32_t expected = values[(size_t(y) * w + x) * channels + c];
                        EXPECT_EQ(std::lround(image.at(x, y, c) * float(maxValue)), long(expected));
                        // OpenCV orders colour channels B, G, R (then alpha).
                        const uint32_t cvChannel = channels >= 3 && c < 3 ? 2 - c : c;
                        const uint32_t read = bits == 8 ? cvImage.ptr<uint8_t>(int(y))[x * channels + cvChannel]
                                                        : cvImage.ptr<uint16_t>(int(y))[x * channels + cvChannel];
                        EXPECT_EQ(read, expected) << path << " (" << x << ", " << y << ") channel " << c;
                    }
        }
    sward::test::expectError([&] { writePng8(dir + "/short.png", w, h, 3, std::vector<uint8_t>(w * h * 3 - 1)); },
                             {"PNG buffer size does not match the image"});
    EXPECT_FALSE(std::filesystem::exists(dir + "/short.png"));
    sward::test::expectError([&] { writePng16(dir + "/ga.png", w, h, 2, std::vector<uint16_t>(w * h * 2)); },
                             {dir + "/ga.png", "a PNG of 2 channels"});
}

// sward calls libpng itself (io/image_files.cpp), in every build, with OpenCV's encoder's settings: the files are
// byte for byte those cv::imencode wrote when sward encoded through it, so no dataset changed when the build without
// OpenCV came (issue 49). Flat runs, ramps and hashed noise (zlib's run-length and literal paths, the sub filter's
// wrap-around), 8 and 16 bits, grey, RGB and RGBA, one image over several of zlib's blocks.
TEST(PngFiles, SameBytesAsOpenCvsEncoder) {
    const std::string dir = sward::test::tempDir().string();
    for (const auto& [w, h] : {std::pair<uint32_t, uint32_t>{61, 37}, {320, 240}})
        for (uint32_t bits : {8u, 16u})
            for (uint32_t channels : {1u, 3u, 4u}) {
                const std::string path = dir + "/p" + std::to_string(w) + "-" + std::to_string(bits) + "-" +
                                         std::to_string(channels) + ".png";
                const uint32_t maxValue = bits == 8 ? 255u : 65535u;
                std::vector<uint32_t> values(size_t(w) * h * channels);
                for (size_t i = 0; i < values.size(); ++i) {
                    const size_t pixel = i / channels, x = pixel % w, y = pixel / w;
                    const uint32_t noise = uint32_t(hashKey({i, bits, channels}));
                    values[i] = y < h / 3   ? uint32_t(x * 4 + i % channels) % (maxValue + 1) // ramps
                                : y < h / 2 ? maxValue / 3                                    // one flat run
                                            : noise % (maxValue + 1);                         // noise
                }
                if (bits == 8)
                    writePng8(path, w, h, channels, std::vector<uint8_t>(values.begin(), values.end()));
                else
                    writePng16(path, w, h, channels, std::vector<uint16_t>(values.begin(), values.end()));
                cv::Mat image(int(h), int(w), CV_MAKETYPE(bits == 8 ? CV_8U : CV_16U, int(channels)));
                for (uint32_t y = 0; y < h; ++y)
                    for (uint32_t x = 0; x < w; ++x)
                        for (uint32_t c = 0; c < channels; ++c) {
                            const uint32_t cvChannel = channels >= 3 && c < 3 ? 2 - c : c; // B, G, R (then alpha)
                            const uint32_t value = values[(size_t(y) * w + x) * channels + c];
                            if (bits == 8)
                                image.ptr<uint8_t>(int(y))[x * channels + cvChannel] = uint8_t(value);
                            else
                                image.ptr<uint16_t>(int(y))[x * channels + cvChannel] = uint16_t(value);
                        }
                std::vector<uint8_t> expected;
                ASSERT_TRUE(cv::imencode(".png", image, expected));
                std::ifstream file(path, std::ios::binary);
                const std::vector<uint8_t> written{std::istreambuf_iterator<char>(file), {}};
                EXPECT_EQ(written.size(), expected.size()) << path;
                EXPECT_TRUE(written == expected) << path;
            }
}

TEST(PngFiles, AHeaderClaimingMorePixelsThanTheFileCanHoldIsRefused) {
    const std::string path = sward::test::tempDir().string() + "/huge.png";
    sward::test::writePng(path, 1, 1, 1, 8, {0.5f});
    std::vector<char> bytes = readAll(path);
    // IHDR width and height (big-endian) at bytes 16 and 20: 30000x30000 grey is 900 MB of deflate output,
    // far beyond the 1032:1 that deflate can expand this file's few dozen bytes to.
    for (size_t at : {16u, 20u}) {
        bytes[at] = 0, bytes[at + 1] = 0, bytes[at + 2] = char(30000 >> 8), bytes[at + 3] = char(30000 & 0xff);
    }
    writeAll(path, bytes);
    sward::test::expectError([&] { loadImage(path); }, {path, "claims 30000x30000 pixels", "truncated or corrupt PNG"});
}

// A PNG of the stated size with `idatBytes` bytes of image data (not a valid deflate stream: the header's checks
// come first).
std::vector<char> pngHeaderWithData(uint32_t width, uint32_t height, uint8_t colourType, size_t idatBytes) {
    std::vector<char> bytes = {char(0x89), 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    auto be32 = [&](uint32_t v) {
        for (int shift : {24, 16, 8, 0}) bytes.push_back(char((v >> shift) & 0xff));
    };
    auto chunk = [&](const char* type, size_t length, const std::vector<char>& body) {
        be32(uint32_t(length));
        bytes.insert(bytes.end(), type, type + 4);
        bytes.insert(bytes.end(), body.begin(), body.end());
        bytes.resize(bytes.size() + (length - body.size()), 0);
        be32(0); // the CRC: never checked before the decode
    };
    std::vector<char> ihdr;
    for (uint32_t v : {width, height})
        for (int shift : {24, 16, 8, 0}) ihdr.push_back(char((v >> shift) & 0xff));
    ihdr.insert(ihdr.end(), {8, char(colourType), 0, 0, 0});
    chunk("IHDR", ihdr.size(), ihdr);
    chunk("IDAT", idatBytes, {});
    chunk("IEND", 0, {});
    return bytes;
}

// A 1 MB PNG of 16384x16384 RGB (a grass map) took 10.4 GB and 105 s: 4 GiB decoded is refused from the header.
TEST(PngFiles, ADecodeOverTheByteBudgetIsRefusedFromTheHeader) {
    const std::vector<char> bytes = pngHeaderWithData(16384, 16384, 2, 800000);
    sward::test::expectError([&] { decodePng("map.png", bytes); },
                             {"image 'map.png' (16384x16384, 3 channels) would take 3840 MiB decoded, over the limit "
                              "of 2048 MiB"});
}

// Textures decode straight to 8-bit RGBA, with the values the float path gave (grey widened, alpha 255 when absent).
TEST(PngFiles, Rgba8DecodingMatchesTheFloatSamplesRounded) {
    const std::string dir = sward::test::tempDir().string();
    for (uint8_t bits : {uint8_t(8), uint8_t(16)})
        for (uint32_t channels : {1u, 2u, 3u, 4u}) {
            const std::string path = dir + "/t" + std::to_string(bits) + "-" + std::to_string(channels) + ".png";
            std::vector<float> samples(3 * 2 * channels);
            for (size_t i = 0; i < samples.size(); ++i) samples[i] = float((i * 37) % 101) / 100.0f;
            sward::test::writePng(path, 3, 2, channels, bits, samples);
            const ImageData image = loadImage(path);
            uint32_t width = 0, height = 0;
            const std::vector<unsigned char> rgba = decodePngRgba8(path, readAll(path), kMaxImageEdge, width, height);
            ASSERT_EQ(width, 3u);
            ASSERT_EQ(height, 2u);
            ASSERT_EQ(rgba.size(), 3u * 2 * 4);
            for (uint32_t p = 0; p < 6; ++p) {
                auto at = [&](uint32_t c) { return std::lround(image.samples[p * channels + c] * 255.0f); };
                const bool colour = channels >= 3;
                const long expected[4] = {at(0), colour ? at(1) : at(0), colour ? at(2) : at(0),
                                          channels == 4   ? at(3)
                                          : channels == 2 ? at(1)
                                                          : 255};
                for (int c = 0; c < 4; ++c)
                    EXPECT_EQ(long(rgba[4 * p + size_t(c)]), expected[c]) << path << " pixel " << p << " channel " << c;
            }
        }
}
// A ground texture's edge limit is checked before the decode (a 16384^2 texture was decoded, 3.9 GB, first).
TEST(PngFiles, ACallersEdgeLimitIsCheckedBeforeTheDecode) {
    const std::vector<char> bytes = pngHeaderWithData(16384, 16, 6, 4000);
    sward::test::expectError([&] { decodePng("tex.png", bytes, 8192); },
                             {"image 'tex.png' has size 16384x16", "each edge must be 1..8192 pixels"});
}

TEST(ExrFiles, ADataWindowBeyondTheEdgeLimitIsRefusedBeforeOpenExrAllocatesItsTables) {
    // OpenEXR sizes its line-offset table from the data window in its constructor: 2^30 lines are 8 GiB.
    const std::string path = sward::test::tempDir().string() + "/tall.exr";
    writeExr(path, 2, 2, 1, std::vector<float>(4, 1.0f));
    std::vector<char> bytes = readAll(path);
    const std::string key("dataWindow\0box2i\0", 17);
    const auto at = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
    ASSERT_NE(at, bytes.end());
    const int32_t maxY = 1 << 30;
    std::memcpy(&*(at + 17 + 4 + 12), &maxY, 4); // after the size: min x, min y, max x, max y
    writeAll(path, bytes);
    sward::test::expectError([&] { loadImage(path); }, {path, "has size 2x1073741825", "each edge must be 1..32768"});
}

TEST(ImageFiles, APipeOrDeviceIsRefusedInsteadOfReadForever) {
    const std::string fifo = sward::test::tempDir().string() + "/pipe.png";
    std::filesystem::remove(fifo);
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    sward::test::expectError([&] { loadImage(fifo); }, {fifo, "not a regular file"});
    sward::test::expectError([&] { readImageFileBytes("/dev/zero"); }, {"/dev/zero", "not a regular file"});
}

namespace {

float hsvSaturation(std::array<float, 3> c) {
    const float peak = std::max({c[0], c[1], c[2]});
    return peak > 0.0f ? 1.0f - std::min({c[0], c[1], c[2]}) / peak : 0.0f;
}

// Saturated plant, flower and sky colours (linear radiance), each over intensities from deep shadow to 8x sunlit.
const std::array<float, 3> kSaturatedColours[] = {
    {0.10f, 0.30f, 0.04f}, {0.25f, 0.22f, 0.03f}, {0.9f, 0.05f, 0.02f}, {0.05f, 0.2f, 0.9f}, {0.6f, 0.5f, 0.45f}};
const float kIntensities[] = {0.01f, 0.03f, 0.1f, 0.2f, 0.4f, 0.7f, 1.0f, 1.5f, 2.0f, 3.0f, 5.0f, 8.0f};

} // namespace

TEST(ToneCurve, DoesNotRaiseSaturation) {
    // The curve per channel took sward's meadow from saturation 0.64 to 0.83: its toe steepens the ratios.
    for (const auto& colour : kSaturatedColours)
        for (float k : kIntensities) {
            std::array<float, 3> linear{colour[0] * k, colour[1] * k, colour[2] * k};
            std::array<float, 3> mapped = toneMap(linear, 0.5f);
            EXPECT_LE(hsvSaturation(mapped), hsvSaturation(linear) + 1e-5f)
                << linear[0] << " " << linear[1] << " " << linear[2];
        }
}

TEST(ToneCurve, KeepsHueBelowClippingAndFadesToWhiteAbove) {
    const std::array<float, 3> green{0.10f, 0.30f, 0.04f};
    std::array<float, 3> mapped = toneMap(green, 0.5f);
    EXPECT_NEAR(mapped[0] / mapped[1], green[0] / green[1], 1e-5f);
    EXPECT_NEAR(mapped[2] / mapped[1], green[2] / green[1], 1e-5f);
    std::array<float, 3> bright = toneMap({green[0] * 100.0f, green[1] * 100.0f, green[2] * 100.0f}, 0.5f);
    EXPECT_LE(std::max({bright[0], bright[1], bright[2]}), 1.0f);
    EXPECT_LT(hsvSaturation(bright), 0.5f * hsvSaturation(green));
}

TEST(ToneCurve, GreyStaysGrey) {
    for (float k : kIntensities) {
        std::vector<uint8_t> rgb = tonemapPreview(std::vector<uint16_t>(4, floatToHalfBits(k)), 1, 1);
        EXPECT_EQ(rgb[0], rgb[1]) << k;
        EXPECT_EQ(rgb[1], rgb[2]) << k;
    }
}

TEST(ToneCurve, IsMonotonicInIntensity) {
    for (const auto& colour : kSaturatedColours) {
        std::array<float, 3> previous{0.0f, 0.0f, 0.0f};
        std::vector<uint8_t> previousBytes(3, 0);
        for (int step = 1; step <= 400; ++step) {
            float k = 0.02f * float(step);
            std::array<float, 3> mapped = toneMap({colour[0] * k, colour[1] * k, colour[2] * k}, 0.5f);
            std::vector<uint16_t> half{floatToHalfBits(colour[0] * k), floatToHalfBits(colour[1] * k),
                                       floatToHalfBits(colour[2] * k), floatToHalfBits(1.0f)};
            std::vector<uint8_t> bytes = tonemapPreview(half, 1, 1);
            for (int c = 0; c < 3; ++c) {
                EXPECT_GE(mapped[c], previous[c] - 1e-6f) << k;
                EXPECT_GE(bytes[c], previousBytes[c]) << k;
            }
            previous = mapped;
            previousBytes = bytes;
        }
    }
}

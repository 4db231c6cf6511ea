// Test helpers that write small input files (PNG of any bit depth, glTF) into a per-test temporary folder,
// so that no binary file is committed. PNGs are written uncompressed (stored deflate blocks): valid, and tiny
// enough for test images.
#pragma once

#include "common/error.h"
#include "common/optional_components.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <iterator>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace sward::test {

// Skips the test in a build without the optional component (docs/release.md, "A lean build"), for the few tests that
// need it in files whose other tests do not (whole files are left out in tests/CMakeLists.txt).
#define SWARD_SKIP_WITHOUT(component)                                                                                  \
    if (!::sward::hasComponent(::sward::Component::component))                                                         \
    GTEST_SKIP() << "this build of sward leaves out " #component

// A fresh folder per test, named after it.
inline std::filesystem::path tempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    auto dir = std::filesystem::temp_directory_path() /
               ("sward_tests_" + std::string(info->test_suite_name()) + "_" + info->name());
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// The whole content of a file ("" when it cannot be read).
inline std::string readText(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

// The pid of a process that has surely ended (a child that exited and was reaped): it names a dead writer.
inline long deadPid() {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    ::waitpid(child, nullptr, 0);
    return long(child);
}

inline uint32_t crc32(const unsigned char* data, size_t size, uint32_t crc = 0) {
    crc = ~crc;
    for (size_t i = 0; i < size; ++i) {
        crc ^= data[i];
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

// colorType: 0 grey, 2 RGB, 4 grey+alpha, 6 RGBA. rows: already packed per PNG rules (big-endian 16-bit
// samples, sub-byte samples packed MSB first), without filter bytes.
inline void writePngRaw(const std::filesystem::path& path, uint32_t width, uint32_t height, uint8_t bitDepth,
                        uint8_t colorType, const std::vector<uint8_t>& packedRows) {
    const size_t rowBytes = packedRows.size() / height;
    std::vector<uint8_t> raw;
    for (uint32_t y = 0; y < height; ++y) {
        raw.push_back(0); // filter: none
        raw.insert(raw.end(), packedRows.begin() + y * rowBytes, packedRows.begin() + (y + 1) * rowBytes);
    }
    std::vector<uint8_t> z = {0x78, 0x01};
    uint32_t a = 1, b = 0;
    for (uint8_t v : raw) a = (a + v) % 65521, b = (b + a) % 65521;
    for (size_t pos = 0; pos < raw.size() || pos == 0; pos += 65535) {
        const size_t len = std::min<size_t>(65535, raw.size() - pos);
        z.push_back(pos + len >= raw.size() ? 1 : 0);
        z.insert(z.end(), {uint8_t(len), uint8_t(len >> 8), uint8_t(~len), uint8_t(~len >> 8)});
        z.insert(z.end(), raw.begin() + pos, raw.begin() + pos + len);
        if (raw.empty()) break;
    }
    const uint32_t adler = (b << 16) | a;
    z.insert(z.end(), {uint8_t(adler >> 24), uint8_t(adler >> 16), uint8_t(adler >> 8), uint8_t(adler)});

    std::ofstream out(path, std::ios::binary);
    auto be32 = [](uint32_t v) {
        return std::vector<uint8_t>{uint8_t(v >> 24), uint8_t(v >> 16), uint8_t(v >> 8), uint8_t(v)};
    };
    auto chunk = [&](const char* type, const std::vector<uint8_t>& data) {
        std::vector<uint8_t> body(type, type + 4);
        body.insert(body.end(), data.begin(), data.end());
        auto len = be32(uint32_t(data.size())), crc = be32(crc32(body.data(), body.size()));
        out.write((const char*)len.data(), 4);
        out.write((const char*)body.data(), std::streamsize(body.size()));
        out.write((const char*)crc.data(), 4);
    };
    const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    out.write((const char*)signature, 8);
    std::vector<uint8_t> ihdr = be32(width);
    auto h = be32(height);
    ihdr.insert(ihdr.end(), h.begin(), h.end());
    ihdr.insert(ihdr.end(), {bitDepth, colorType, 0, 0, 0});
    chunk("IHDR", ihdr);
    chunk("IDAT", z);
    chunk("IEND", {});
}

// 8- or 16-bit PNG from normalised samples (channels 1..4 interleaved, top row first).
inline void writePng(const std::filesystem::path& path, uint32_t width, uint32_t height, uint32_t channels,
                     uint8_t bitDepth, const std::vector<float>& samples) {
    static const uint8_t kColorType[] = {0, 0, 4, 2, 6};
    std::vector<uint8_t> rows;
    for (float s : samples) {
        const uint32_t max = bitDepth == 16 ? 65535 : 255;
        const uint32_t v = uint32_t(std::clamp(s, 0.0f, 1.0f) * float(max) + 0.5f);
        if (bitDepth == 16) rows.push_back(uint8_t(v >> 8));
        rows.push_back(uint8_t(v));
    }
    writePngRaw(path, width, height, bitDepth, kColorType[channels], rows);
}

// Runs f, expecting a sward::Error whose message contains every fragment.
inline void expectError(const std::function<void()>& f, std::initializer_list<std::string> fragments) {
    try {
        f();
        ADD_FAILURE() << "expected sward::Error";
    } catch (const Error& e) {
        for (const std::string& fragment : fragments)
            EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos)
                << "message \"" << e.what() << "\" lacks \"" << fragment << "\"";
    }
}

// The message of the sward::Error that f throws; "" when it throws none (so an assertion shows what was said).
inline std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

inline std::string base64(const std::vector<uint8_t>& bytes) {
    static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t v = uint32_t(bytes[i]) << 16;
        if (i + 1 < bytes.size()) v |= uint32_t(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size()) v |= bytes[i + 2];
        const size_t n = std::min<size_t>(3, bytes.size() - i); // n bytes give n + 1 characters
        for (size_t k = 0; k < 4; ++k) out += k <= n ? kAlphabet[(v >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

} // namespace sward::test

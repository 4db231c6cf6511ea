#include "io/sha256.h"

#include "common/error.h"
#include "test_files.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

using namespace sward;

// FIPS 180-4 examples (NIST CSRC "SHA256.pdf", "SHA2_Additional.pdf").
TEST(Sha256, NistOneBlockMessageAbc) {
    EXPECT_EQ(sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(Sha256, EmptyMessage) {
    EXPECT_EQ(sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(Sha256, NistTwoBlockMessage448Bits) {
    EXPECT_EQ(sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
              "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256, NistMessage896Bits) {
    EXPECT_EQ(
        sha256Hex("abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmnoijklmnopjklmnopqklmnopqrlmnopqrsmn"
                  "opqrstnopqrstu"),
        "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1");
}

TEST(Sha256, NistOneMillionA) {
    EXPECT_EQ(sha256Hex(std::string(1000000, 'a')), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
    // Streamed in uneven pieces that straddle block boundaries.
    Sha256 hasher;
    std::string piece(997, 'a');
    size_t left = 1000000;
    while (left > 0) {
        size_t n = std::min(left, piece.size());
        hasher.update(std::string_view(piece).substr(0, n));
        left -= n;
    }
    EXPECT_EQ(toHex(hasher.finish()), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

// Every split point of messages around the 55/56/64-byte padding boundaries gives the one-shot digest.
TEST(Sha256, IncrementalEqualsOneShotAtEverySplit) {
    for (size_t length : {55u, 56u, 63u, 64u, 65u, 119u, 120u, 130u}) {
        std::string message;
        for (size_t i = 0; i < length; ++i) message.push_back(char('A' + (i * 7) % 26));
        std::string expected = sha256Hex(message);
        for (size_t split = 0; split <= length; ++split) {
            Sha256 hasher;
            hasher.update(std::string_view(message).substr(0, split));
            hasher.update(std::string_view(message).substr(split));
            ASSERT_EQ(toHex(hasher.finish()), expected) << "length " << length << " split " << split;
        }
    }
}

TEST(Sha256, FileIsStreamedAndMatchesBytes) {
    auto path = (test::tempDir() / "million.bin").string();
    std::string content(1000000, 'a');
    content += "tail beyond one read block";
    std::ofstream(path, std::ios::binary) << content;
    EXPECT_EQ(sha256File(path), sha256Hex(content));
    std::ofstream(path, std::ios::binary | std::ios::trunc) << std::string(1000000, 'a');
    EXPECT_EQ(sha256File(path), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, MissingFileNamesIt) {
    auto path = (test::tempDir() / "absent.exr").string();
    try {
        sha256File(path);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
}

// The SHA extensions (Sha256::Implementation::Fastest on a CPU that has them) against the portable code: every
// length around the block and padding boundaries, many blocks at once, and streamed in uneven pieces.
TEST(Sha256, ShaExtensionsGiveThePortableDigests) {
    if (!Sha256::accelerated()) GTEST_SKIP() << "this CPU has no SHA extensions: Fastest is the portable code";
    std::string message;
    uint32_t x = 12345u;
    for (size_t i = 0; i < (1u << 20) + 77; ++i) {
        x = x * 1664525u + 1013904223u; // any bytes will do; these are the same every run
        message.push_back(char(x >> 24));
    }
    auto digest = [&](Sha256::Implementation implementation, size_t length, size_t piece) {
        Sha256 hasher(implementation);
        for (size_t at = 0; at < length; at += piece)
            hasher.update(std::string_view(message).substr(at, std::min(piece, length - at)));
        return toHex(hasher.finish());
    };
    for (size_t length = 0; length <= 300; ++length)
        ASSERT_EQ(digest(Sha256::Implementation::Fastest, length, 1000),
                  digest(Sha256::Implementation::Portable, length, 1000))
            << "length " << length;
    for (size_t piece : {1u, 63u, 64u, 4096u, 1u << 20})
        ASSERT_EQ(digest(Sha256::Implementation::Fastest, message.size(), piece),
                  digest(Sha256::Implementation::Portable, message.size(), piece))
            << "piece " << piece;
}

// The NIST vectors through the portable code too (the other tests take Fastest, the SHA extensions where present).
TEST(Sha256, PortableCodeGivesTheNistDigests) {
    auto portable = [](std::string_view text) {
        Sha256 hasher(Sha256::Implementation::Portable);
        hasher.update(text);
        return toHex(hasher.finish());
    };
    EXPECT_EQ(portable("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    EXPECT_EQ(portable("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
              "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
    EXPECT_EQ(portable(std::string(1000000, 'a')), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

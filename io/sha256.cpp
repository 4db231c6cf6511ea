#include "io/sha256.h"

#include "common/error.h"
#include "common/input_file.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cerrno>
#include <cstring>
#include <unistd.h>
#include <vector>

// The x86 SHA extensions, chosen at run time (GCC and Clang on x86-64).
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define SWARD_SHA_EXTENSIONS 1
#include <cpuid.h>
#include <immintrin.h>
#else
#define SWARD_SHA_EXTENSIONS 0
#endif

namespace sward {

namespace {

constexpr std::array<uint32_t, 64> kRound = {
    0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5,
    0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174,
    0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da,
    0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967,
    0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85,
    0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070,
    0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
    0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2};

// FIPS 180-4 5.3.3: the state before the first block.
constexpr std::array<uint32_t, 8> kInitialState = {0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a,
                                                   0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19};

uint32_t loadBigEndian(const uint8_t* p) {
    return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
}

// FIPS 180-4's compression of one block, written out.
void compressPortable(std::array<uint32_t, 8>& state, const uint8_t* block) {
    uint32_t w[64];
    for (int t = 0; t < 16; ++t) w[t] = loadBigEndian(block + 4 * t);
    for (int t = 16; t < 64; ++t) {
        uint32_t s0 = std::rotr(w[t - 15], 7) ^ std::rotr(w[t - 15], 18) ^ (w[t - 15] >> 3);
        uint32_t s1 = std::rotr(w[t - 2], 17) ^ std::rotr(w[t - 2], 19) ^ (w[t - 2] >> 10);
        w[t] = w[t - 16] + s0 + w[t - 7] + s1;
    }
    uint32_t a = state[0], b = state[1], c = state[2], d = state[3];
    uint32_t e = state[4], f = state[5], g = state[6], h = state[7];
    for (int t = 0; t < 64; ++t) {
        uint32_t s1 = std::rotr(e, 6) ^ std::rotr(e, 11) ^ std::rotr(e, 25);
        uint32_t choose = (e & f) ^ (~e & g);
        uint32_t t1 = h + s1 + choose + kRound[size_t(t)] + w[t];
        uint32_t s0 = std::rotr(a, 2) ^ std::rotr(a, 13) ^ std::rotr(a, 22);
        uint32_t majority = (a & b) ^ (a & c) ^ (b & c);
        uint32_t t2 = s0 + majority;
        h = g;
        g = f;
        f = e;
        e = d + t1;
        d = c;
        c = b;
        b = a;
        a = t1 + t2;
    }
    state[0] += a, state[1] += b, state[2] += c, state[3] += d;
    state[4] += e, state[5] += f, state[6] += g, state[7] += h;
}

#if SWARD_SHA_EXTENSIONS
bool cpuHasShaExtensions() {
    unsigned a, b, c, d;
    if (!__get_cpuid(1, &a, &b, &c, &d) || !(c & bit_SSSE3) || !(c & bit_SSE4_1)) return false;
    return __get_cpuid_count(7, 0, &a, &b, &c, &d) && (b & bit_SHA);
}

// The same compression with the SHA extensions (Intel's "SHA extensions" paper): the state is kept as the two
// vectors the round instruction takes, ABEF and CDGH; each step of 4 rounds adds the round constants to 4 message
// words, runs 2 + 2 rounds, and extends the message schedule 4 words at a time (sha256msg1 / sha256msg2).
__attribute__((target("sha,sse4.1,ssse3"))) void compressWithShaExtensions(std::array<uint32_t, 8>& state,
                                                                           const uint8_t* data, size_t blocks) {
    const __m128i byteSwap = _mm_set_epi8(12, 13, 14, 15, 8, 9, 10, 11, 4, 5, 6, 7, 0, 1, 2, 3);
    const __m128i dcba = _mm_shuffle_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(&state[0])), 0xB1);
    const __m128i efgh = _mm_shuffle_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(&state[4])), 0x1B);
    __m128i abef = _mm_alignr_epi8(dcba, efgh, 8);
    __m128i cdgh = _mm_blend_epi16(efgh, dcba, 0xF0);
    for (; blocks > 0; --blocks, data += 64) {
        const __m128i abefBefore = abef, cdghBefore = cdgh;
        __m128i w[4]; // message words 4i..4i+3 of step i live in w[i % 4]
#pragma GCC unroll 16 // unrolled, w[] and the step's conditions vanish into registers and straight-line code
        for (int i = 0; i < 16; ++i) {
            __m128i& words = w[i % 4];
            if (i < 4)
                words = _mm_shuffle_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(data + 16 * i)), byteSwap);
            __m128i k = _mm_add_epi32(words, _mm_loadu_si128(reinterpret_cast<const __m128i*>(&kRound[size_t(4 * i)])));
            cdgh = _mm_sha256rnds2_epu32(cdgh, abef, k);
            if (i >= 3 && i <= 14) { // words of step i + 1: w[(i + 1) % 4] holds their sha256msg1 part already
                __m128i& next = w[(i + 1) % 4];
                next = _mm_sha256msg2_epu32(_mm_add_epi32(next, _mm_alignr_epi8(words, w[(i + 3) % 4], 4)), words);
            }
            abef = _mm_sha256rnds2_epu32(abef, cdgh, _mm_shuffle_epi32(k, 0x0E));
            if (i >= 1 && i <= 12) w[(i + 3) % 4] = _mm_sha256msg1_epu32(w[(i + 3) % 4], words);
        }
        abef = _mm_add_epi32(abef, abefBefore);
        cdgh = _mm_add_epi32(cdgh, cdghBefore);
    }
    const __m128i feba = _mm_shuffle_epi32(abef, 0x1B);
    const __m128i dchg = _mm_shuffle_epi32(cdgh, 0xB1);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(&state[0]), _mm_blend_epi16(feba, dchg, 0xF0));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(&state[4]), _mm_alignr_epi8(dchg, feba, 8));
}
#endif

} // namespace

Sha256::Sha256(Implementation implementation)
    : accelerated_(implementation == Implementation::Fastest && accelerated()), state_(kInitialState) {}

bool Sha256::accelerated() {
#if SWARD_SHA_EXTENSIONS
    static const bool has = cpuHasShaExtensions();
    return has;
#else
    return false;
#endif
}

void Sha256::compress(const uint8_t* data, size_t blocks) {
#if SWARD_SHA_EXTENSIONS
    if (accelerated_) return compressWithShaExtensions(state_, data, blocks);
#endif
    for (; blocks > 0; --blocks, data += 64) compressPortable(state_, data);
}

void Sha256::update(std::span<const uint8_t> bytes) {
    assert(!finished_);
    totalBytes_ += bytes.size();
    const uint8_t* p = bytes.data();
    size_t n = bytes.size();
    if (buffered_ > 0) {
        size_t take = std::min(n, buffer_.size() - buffered_);
        std::memcpy(buffer_.data() + buffered_, p, take);
        buffered_ += take, p += take, n -= take;
        if (buffered_ < buffer_.size()) return;
        compress(buffer_.data(), 1);
        buffered_ = 0;
    }
    compress(p, n / 64);
    p += n / 64 * 64, n %= 64;
    if (n > 0) std::memcpy(buffer_.data(), p, n);
    buffered_ = n;
}

std::array<uint8_t, 32> Sha256::finish() {
    assert(!finished_);
    // Padding: 0x80, zeros up to 56 mod 64, then the message length in bits as a big-endian 64-bit number.
    uint64_t bits = totalBytes_ * 8;
    uint8_t pad[72] = {0x80};
    size_t padLength = (buffered_ < 56 ? 56 : 120) - buffered_;
    for (int i = 0; i < 8; ++i) pad[padLength + size_t(i)] = uint8_t(bits >> (56 - 8 * i));
    update({pad, padLength + 8});
    assert(buffered_ == 0);
    finished_ = true;
    std::array<uint8_t, 32> digest;
    for (size_t i = 0; i < 8; ++i)
        for (size_t k = 0; k < 4; ++k) digest[i * 4 + k] = uint8_t(state_[i] >> (24 - 8 * k));
    return digest;
}

std::string toHex(std::span<const uint8_t> bytes) {
    static const char* digits = "0123456789abcdef";
    std::string hex;
    hex.reserve(bytes.size() * 2);
    for (uint8_t b : bytes) hex.append({digits[b >> 4], digits[b & 15]});
    return hex;
}

std::string sha256Hex(std::span<const uint8_t> bytes) {
    Sha256 hasher;
    hasher.update(bytes);
    return toHex(hasher.finish());
}

std::string sha256Hex(std::string_view text) {
    return sha256Hex(std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

std::string sha256File(const std::string& path) {
    const InputFile file = openInputFile(path, "file to hash"); // a FIFO or a device is refused, never read
    Sha256 hasher;
    std::vector<uint8_t> block(1 << 20);
    for (;;) {
        const ssize_t n = ::read(file.fd(), block.data(), block.size());
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw Error("cannot read '" + path + "' to hash it: " + std::strerror(errno));
        if (n == 0) break;
        hasher.update({block.data(), size_t(n)});
    }
    return toHex(hasher.finish());
}

} // namespace sward

// SHA-256 (FIPS 180-4) of bytes and files, as lowercase hex: the per-file hashes of dataset manifests.
//
// Own implementation so the core needs no crypto library: the portable code (FIPS 180-4 written out) and, chosen at
// run time, the x86 SHA extensions, 5-8x faster (docs/benchmarks.md). Not constant-time: meant for integrity
// checks, not secrets.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace sward {

// Incremental hasher: update() any number of times, then finish() once.
class Sha256 {
public:
    // Fastest: the x86 SHA extensions where the CPU has them (5x the portable code on a dataset's files, which its
    // manifest hashes), else the portable code. Both give the same digest; tests compare them.
    enum class Implementation { Fastest, Portable };
    explicit Sha256(Implementation implementation = Implementation::Fastest);
    // Whether Fastest uses the SHA extensions on this CPU.
    static bool accelerated();

    void update(std::span<const uint8_t> bytes);
    void update(std::string_view text) { update({reinterpret_cast<const uint8_t*>(text.data()), text.size()}); }
    std::array<uint8_t, 32> finish();

private:
    // Folds `blocks` 64-byte blocks into state_.
    void compress(const uint8_t* data, size_t blocks);
    bool accelerated_ = false;
    std::array<uint32_t, 8> state_;
    std::array<uint8_t, 64> buffer_{};
    size_t buffered_ = 0;
    uint64_t totalBytes_ = 0;
    bool finished_ = false;
};

std::string toHex(std::span<const uint8_t> bytes);
std::string sha256Hex(std::span<const uint8_t> bytes);
std::string sha256Hex(std::string_view text);
// Streams the file in blocks; throws sward::Error naming the file when it cannot be read.
std::string sha256File(const std::string& path);

} // namespace sward

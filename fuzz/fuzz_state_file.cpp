// Interaction state files through loadInteractionState and world state files through loadWorldState (one family:
// the same conventions, seeds of both in corpus/state_file/). The harness rewrites the trailing FNV-1a checksum to match
// the bytes before it: otherwise almost every mutation stops at the checksum and the parser behind it is never
// reached (the mismatch itself is covered by tests/interaction/state_file_test.cpp).
#include "fuzz/fuzz_input.h"
#include "interaction/state_file.h"

#include <cstring>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::vector<uint8_t> bytes(data, data + size);
    if (bytes.size() >= 8) {
        const uint64_t sum = sward::fnv1a64(std::span(bytes.data(), bytes.size() - 8));
        std::memcpy(bytes.data() + bytes.size() - 8, &sum, 8); // little-endian host, as the file layout
    }
    const std::string path = sward::fuzz::inputFile(bytes.data(), bytes.size(), "state.bin");
    sward::fuzz::expectOnlyErrors([&] { sward::loadInteractionState(path); });
    return sward::fuzz::expectOnlyErrors([&] { sward::loadWorldState(path, 1); }); // the seeds' seed (make-seeds.py)
}

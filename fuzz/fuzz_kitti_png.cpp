// KITTI 16-bit disparity PNGs through readKittiPng (sward-eval's estimates of other matchers).
#include "fuzz/fuzz_input.h"
#include "io/disparity_files.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = sward::fuzz::inputFile(data, size, "disparity.png");
    return sward::fuzz::expectOnlyErrors([&] { sward::readKittiPng(path); });
}

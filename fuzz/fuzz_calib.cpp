// Middlebury calib.txt through readMiddleburyCalib (sward-eval reads the dataset's calibration this way).
#include "fuzz/fuzz_input.h"
#include "io/disparity_files.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = sward::fuzz::inputFile(data, size, "calib.txt");
    return sward::fuzz::expectOnlyErrors([&] { sward::readMiddleburyCalib(path); });
}

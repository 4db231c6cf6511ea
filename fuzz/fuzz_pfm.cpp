// PFM disparity maps through readPfm (sward-eval's ground truth and other matchers' estimates).
#include "fuzz/fuzz_input.h"
#include "io/disparity_files.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = sward::fuzz::inputFile(data, size, "disparity.pfm");
    return sward::fuzz::expectOnlyErrors([&] { sward::readPfm(path); });
}

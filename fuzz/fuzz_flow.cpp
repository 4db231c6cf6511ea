// Optical-flow files through readFlo and readKittiFlowPng (sward-eval flow's ground truth and other methods'
// estimates): the first byte picks the reader.
#include "fuzz/fuzz_input.h"
#include "io/flow_files.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    const bool png = data[0] & 1;
    const std::string path = sward::fuzz::inputFile(data + 1, size - 1, png ? "flow.png" : "flow.flo");
    return sward::fuzz::expectOnlyErrors(
        [&] { png ? (void)sward::readKittiFlowPng(path) : (void)sward::readFlo(path); });
}

// OpenEXR images through loadImage: sward-eval's ground-truth disparity and float grass maps read this way.
#include "fuzz/fuzz_input.h"
#include "io/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = sward::fuzz::inputFile(data, size, "image.exr");
    return sward::fuzz::expectOnlyErrors([&] { sward::loadImage(path); });
}

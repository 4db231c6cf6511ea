// Atlases through loadAtlas. The input is the JSON description, a NUL byte, then the PNG (JSON text holds no NUL);
// without a NUL the whole input is the JSON and the PNG is empty.
#include "fuzz/fuzz_input.h"
#include "vegetation/atlas.h"

#include <algorithm>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const uint8_t* split = std::find(data, data + size, uint8_t(0));
    const std::string json = sward::fuzz::inputFile(data, size_t(split - data), "atlas.json");
    const uint8_t* png = split == data + size ? split : split + 1;
    const std::string image = sward::fuzz::inputFile(png, size_t(data + size - png), "atlas.png");
    return sward::fuzz::expectOnlyErrors([&] { sward::loadAtlas(image, json); });
}

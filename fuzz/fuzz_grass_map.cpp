// Grass maps through loadGrassMap, PNG or EXR as the input's first bytes say (the loader picks by extension).
#include "fuzz/fuzz_input.h"
#include "vegetation/grass_map.h"

#include <cstring>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const uint8_t exrMagic[4] = {0x76, 0x2f, 0x31, 0x01};
    const bool exr = size >= 4 && std::memcmp(data, exrMagic, 4) == 0;
    const std::string path = sward::fuzz::inputFile(data, size, exr ? "grass.exr" : "grass.png");
    return sward::fuzz::expectOnlyErrors([&] { sward::loadGrassMap(path); });
}

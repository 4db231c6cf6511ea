// Scene JSON through loadScene: JSON syntax, the schema, every range check and the scene's cross-checks.
#include "fuzz/fuzz_input.h"
#include "scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = sward::fuzz::inputFile(data, size, "scene.json");
    return sward::fuzz::expectOnlyErrors([&] { sward::loadScene(path); });
}

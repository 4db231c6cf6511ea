// .gltf files through both glTF loaders: the object model (node hierarchy) and the flattened ground mesh.
#include "fuzz/fuzz_input.h"
#include "world/gltf_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = sward::fuzz::inputFile(data, size, "model.gltf");
    sward::fuzz::expectOnlyErrors([&] { sward::loadGltfModel(path); });
    return sward::fuzz::expectOnlyErrors([&] { sward::loadGltfMesh(path); });
}

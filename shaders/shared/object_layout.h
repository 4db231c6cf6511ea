// GPU layouts of scene objects (glTF models, vegetation/objects.h), shared by C++ and GLSL (see gpu_layout.h).
// Ground-truth label of object k: (kSemanticObject << kInstanceBits) | (kInstanceObjectBase + k) (gpu_layout.h).
#ifndef SWARD_OBJECT_LAYOUT_H
#define SWARD_OBJECT_LAYOUT_H

#include "gpu_layout.h"

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace sward::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
using uint = uint32_t;
#endif

// One vertex of an object mesh (vertex buffer, binding 0), in its node's frame.
struct ObjectVertex {
    vec4 position;  // xyz node-frame position, metres; w unused
    vec4 normal;    // xyz node-frame unit normal; w unused
    vec4 baseColor; // linear RGBA base colour of the primitive's material
    uvec4 info;     // x index of the node's transform in this frame's ObjectTransform array, y truth label, zw unused
};

// Per-frame transform of one node of one object (storage buffer).
struct ObjectTransform {
    mat4 worldFromNode;
    mat4 normalFromNode; // inverse transpose of worldFromNode (non-uniform node scales keep normals right)
};

#ifdef __cplusplus
static_assert(sizeof(ObjectVertex) == 64);
static_assert(sizeof(ObjectTransform) == 128);
} // namespace sward::gpu
#endif

#endif

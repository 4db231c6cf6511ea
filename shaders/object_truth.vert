#version 460
#extension GL_GOOGLE_include_directive : require
// Scene objects in the truth pass: a non-indexed draw of the objects' index count, vertices and triangle list
// pulled from storage buffers (as terrain_truth.vert), so every vertex passes on its triangle's geometric normal.
// Position, planar depth and label are computed exactly as object.vert computes them.
#include "shared/frame.glsl"
#include "shared/object_layout.h"
#include "shared/flow_vertex.glsl"

layout(set = 0, binding = kBindingObjectTransforms, std430) readonly buffer TransformBlock {
    ObjectTransform transforms[];
};
layout(set = 0, binding = kBindingMeshVertices, std430) readonly buffer VertexBlock { ObjectVertex vertices[]; };
layout(set = 0, binding = kBindingMeshIndices, std430) readonly buffer IndexBlock { uint indices[]; };

layout(location = 2) out float outViewDepth;
layout(location = 4) flat out uint outLabel;
layout(location = 5) flat out vec3 outNormal; // camera frame, unit, facing the camera

void main() {
    uint first = uint(gl_VertexIndex) - uint(gl_VertexIndex) % 3u;
    ObjectVertex vertex = vertices[indices[gl_VertexIndex]];
    ObjectTransform t = transforms[vertex.info.x]; // a triangle never spans two nodes
    vec4 world = t.worldFromNode * vec4(vertex.position.xyz, 1.0);
    gl_Position = frame.viewProj * world;
    outViewDepth = (frame.view * world).z;
    outLabel = vertex.info.y;
    // The edges in the node's frame (exact differences of the model's floats), then the normal transform.
    vec3 q0 = vertices[indices[first]].position.xyz;
    vec3 q1 = vertices[indices[first + 1u]].position.xyz;
    vec3 q2 = vertices[indices[first + 2u]].position.xyz;
    vec3 worldNormal = mat3(t.normalFromNode) * cross(q1 - q0, q2 - q0);
    outNormal = truthNormal(worldNormal, (t.worldFromNode * vec4(q0, 1.0)).xyz);
    // The node's transforms at the previous and the next tick follow this tick's (ObjectRenderer::update).
    const uint perTick = frame.flowParams.x;
    writeFlowVertex((transforms[vertex.info.x + perTick].worldFromNode * vec4(vertex.position.xyz, 1.0)).xyz,
                    (transforms[vertex.info.x + 2u * perTick].worldFromNode * vec4(vertex.position.xyz, 1.0)).xyz);
}

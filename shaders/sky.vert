#version 460
#extension GL_GOOGLE_include_directive : require
// Full-screen triangle at the far plane (reversed Z: depth 0), drawn after the scene with depth test
// GREATER_OR_EQUAL, so only pixels no geometry covered are shaded.
layout(location = 0) out vec2 outNdc;

void main() {
    vec2 ndc = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2) * 2.0 - 1.0;
    outNdc = ndc;
    gl_Position = vec4(ndc, 0.0, 1.0);
}

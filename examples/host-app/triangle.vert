#version 450
// The host's own object: one triangle in the lower middle of the image, drawn over sward's meadow.
void main() {
    const vec2 corners[3] = vec2[](vec2(-0.3, 0.9), vec2(0.3, 0.9), vec2(0.0, 0.3));
    gl_Position = vec4(corners[gl_VertexIndex], 0.5, 1.0);
}

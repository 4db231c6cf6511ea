#version 450
// An emissive red the meadow never has, in the same linear HDR units as sward's colour.
layout(location = 0) out vec4 colour;
void main() {
    colour = vec4(4.0, 0.05, 0.05, 1.0);
}

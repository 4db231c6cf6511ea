#version 460
// The lavapipe floor (sward-bench frame, "floor"): the main pass's plant triangles with the cheapest fragment
// shader there is, one constant colour, no texture, no discard. The plant pass's time over this one's is what the
// shading costs beyond rasterising the same triangles.
layout(location = 0) out vec4 outColor;

void main() { outColor = vec4(0.25, 0.45, 0.15, 1.0); }

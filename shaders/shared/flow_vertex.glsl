// Motion ground truth, vertex side (the truth pass's variants compiled with SWARD_FLOW, render.flow): each vertex
// passes on its point's clip position at the previous and at the next tick, each in that tick's camera. The
// rasteriser interpolates them perspective-correctly, that is with the pixel's barycentric weights on the drawn
// triangle, so a pixel gets exactly where its own point of the triangle moves (flow_fragment.glsl).
#ifndef SWARD_FLOW_VERTEX_GLSL
#define SWARD_FLOW_VERTEX_GLSL
#ifdef SWARD_FLOW

layout(location = 16) out vec4 outClipPrevious;
layout(location = 17) out vec4 outClipNext;

// `previous`, `next`: the vertex's world position at the previous and the next tick.
void writeFlowVertex(vec3 previous, vec3 next) {
    outClipPrevious = frame.viewProjPrevious * vec4(previous, 1.0);
    outClipNext = frame.viewProjNext * vec4(next, 1.0);
}

#else
void writeFlowVertex(vec3 previous, vec3 next) {}
#endif
#endif

// Motion ground truth, fragment side (SWARD_FLOW): attachments 3 and 4 of the truth pass get, for the surface the
// pixel shows, its flow to the next and to the previous tick: x, y the pixel offset of its point there (target pixel
// centre minus this pixel's centre), z that point's planar depth in that tick's camera (clip w = camera z), w 1
// (cleared to 0: no surface).
#ifndef SWARD_FLOW_FRAGMENT_GLSL
#define SWARD_FLOW_FRAGMENT_GLSL
#ifdef SWARD_FLOW

layout(location = 16) in vec4 inClipPrevious;
layout(location = 17) in vec4 inClipNext;
layout(location = 3) out vec4 outFlowForward;
layout(location = 4) out vec4 outFlowBackward;

vec4 flowTo(vec4 clip) {
    vec2 pixel = (clip.xy / clip.w * 0.5 + 0.5) * frame.viewport.xy; // NDC [-1, 1] -> pixels [0, size] (camera.h)
    return vec4(pixel - gl_FragCoord.xy, clip.w, 1.0);
}

void writeFlowFragment() {
    outFlowForward = flowTo(inClipNext);
    outFlowBackward = flowTo(inClipPrevious);
}

#else
void writeFlowFragment() {}
#endif
#endif

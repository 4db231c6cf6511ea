#version 460
#extension GL_GOOGLE_include_directive : require
// terrain.frag with holes: its fragments inside a block drawn as a rut patch are left to the patch
// (render/track_renderer.h).
#define SWARD_TERRAIN_HOLES
#include "shared/terrain_fragment.glsl"

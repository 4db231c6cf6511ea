#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/terrain_fragment.glsl"

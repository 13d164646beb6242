#version 460
#extension GL_GOOGLE_include_directive : require
// compose.comp into an RGBA8 UNORM image (direct and composed RGBA8 UNORM, indirect the kit's
// RGBA32F): the store clamps each channel to [0, 1], so tone map before it or keep direct dim.
#define VPLKIT_COMPOSE_FORMAT rgba8
#include "compose_body.glsl"

#version 460
#extension GL_GOOGLE_include_directive : require
// compose.comp into an RGBA16F image (direct and composed RGBA16F, indirect the kit's RGBA32F).
#define VPLKIT_COMPOSE_FORMAT rgba16f
#include "compose_body.glsl"

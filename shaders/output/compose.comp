#version 460
#extension GL_GOOGLE_include_directive : require
// The frame's radiance: direct plus indirect light, per pixel (both linear RGB, the same size).
// Kept apart until here so that each can be written out (and compared) on its own. RGBA32F; the
// other output formats: compose_rgba16f.comp, compose_rgba8.comp.
#define VPLKIT_COMPOSE_FORMAT rgba32f
#include "compose_body.glsl"

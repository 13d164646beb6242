#version 460
#extension GL_GOOGLE_include_directive : require
// Test-only: the capped 1/r^2 radius sampler of vplkit/brsm.glsl and its pdf, on a regular grid
// of u (the sampler) and of r (the pdf), so the host can check that they are a pair.

#include "vplkit/brsm.glsl"

layout(local_size_x = 64) in;

struct RadiusSample {
    float radius;       // sample_capped_inverse_square_radius((i + 0.5) / n)
    float pdf_at_grid;  // capped_inverse_square_radius_pdf(max_radius (i + 0.5) / n)
};

layout(std430, set = 0, binding = 0) writeonly buffer RadiusSampleBuffer { RadiusSample items[]; } results;

layout(push_constant) uniform RadiusSamplesPush {
    uint count;
    float core;
    float max_radius;
} push;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= push.count) {
        return;
    }
    float t = (float(i) + 0.5) / float(push.count);
    results.items[i].radius = sample_capped_inverse_square_radius(t, push.core, push.max_radius);
    results.items[i].pdf_at_grid = capped_inverse_square_radius_pdf(t * push.max_radius, push.core, push.max_radius);
}

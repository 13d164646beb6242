#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
// Forward light cuts, VPL generation (the FLC paper secs. 3-4): one VPL candidate per scene triangle,
// at its centroid, with the level Alg. 1 draws for it (flc_partition.glsl), or kFlcDiscarded, or
// kFlcDivergent for a triangle larger than S~_N (left to the subdivision path of sec. 6).
// The triangle's uniform number comes from the xor of its three vertices' random integers and the
// frame's (Alg. 2, REGULARRAND), so it follows the triangle under any transform of its mesh.

layout(push_constant) uniform FlcCandidatesPush {
    uint triangle_count;
    uint seed;
    int level_count;  // N + 1
    float s0;         // S_0, world units squared
    float mu;         // > 1
    // raster_scene.glsl's addresses (read only with kSceneAddressed: a scene past a binding's range)
    uvec2 scene_vertex_address;
    uvec2 scene_index_address;
    uint scene_vertex_count;
    uint scene_index_count;
} push;

#define VPLKIT_SCENE_VERTICES_BINDING 0
#define VPLKIT_SCENE_INDICES_BINDING 1
#define VPLKIT_SCENE_PUSH push
#include "vplkit/raster_scene.glsl"
#include "vplkit/flc_candidate.glsl"
#include "vplkit/flc_partition.glsl"
#include "vplkit/rng.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 64) in;

// scene::Scene::vertex_random, one per vertex.
layout(std430, set = 0, binding = 2) readonly buffer VertexRandomBuffer { uint items[]; } vertex_random;

layout(std430, set = 0, binding = 3) writeonly buffer FlcCandidateBuffer { FlcCandidate items[]; } candidates;


void main() {
    uint t = linear_thread_index();
    if (t >= push.triangle_count) {
        return;
    }
    uint i0 = scene_index(3u * t);
    uint i1 = scene_index(3u * t + 1u);
    uint i2 = scene_index(3u * t + 2u);
    vec3 p0 = scene_vertex(i0).position;
    vec3 p1 = scene_vertex(i1).position;
    vec3 p2 = scene_vertex(i2).position;

    // Scaled before squaring so 1e-3-scale triangles (areas ~1e-8) keep their digits.
    vec3 c = cross(p1 - p0, p2 - p0);
    float largest = max(abs(c.x), max(abs(c.y), abs(c.z)));
    float area = largest > 0.0 ? 0.5 * largest * length(c / largest) : 0.0;

    // Alg. 2 xors the frame's number in; hashing the seed first makes seeds 1, 2, 3... change
    // every bit, and hashing the xor makes one triangle's numbers under two seeds unrelated
    // (a plain xor would keep u and u' a fixed bit pattern apart, so averages over seeds would
    // not be over independent draws). A hash is a permutation of 32 bits: u stays uniform.
    uint bits = pcg_hash(vertex_random.items[i0] ^ vertex_random.items[i1] ^ vertex_random.items[i2] ^
                         pcg_hash(push.seed));
    float u = float(bits >> 8u) * (1.0 / 16777216.0);

    int level;
    if (area > flc_divergence_area(push.level_count, push.s0, push.mu)) {
        level = kFlcDivergent;
    } else {
        level = flc_level(u, area, push.level_count, push.s0, push.mu);
    }

    FlcCandidate candidate;
    candidate.position = (p0 + p1 + p2) * (1.0 / 3.0);
    candidate.area = area;
    candidate.normal = largest > 0.0 ? normalize(c / largest) : vec3(0.0);
    candidate.level = level;
    candidates.items[t] = candidate;
}

#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
// Forward light cuts, divergent triangles (the FLC paper sec. 6): a triangle larger than S~_N would need
// a keep probability above one, so it is cut into m x m equal sub-triangles (the regular
// barycentric grid: m^2 triangles of area A / m^2 <= S~_N), and each sub-triangle is a regular
// candidate with its own draw of Alg. 1. The host picks m from the triangle's area alone
// (flc_subdivision_for), so the pattern follows the triangle under any transform, like the paper's
// model-space tessellation. Each sub-triangle's number is Alg. 2's DIVERGENTRAND with a hash of its
// grid corners in place of the noise texture: the xor of the parent's three vertex integers, of its
// three grid corners' hashes and the hashed seed, hashed.
//
// Thread j < triangle_count copies scene triangle j's albedo into the candidates' albedo; thread
// triangle_count + s writes candidate triangle_count + s, sub-triangle s of the subdivision (the
// entry whose range holds s). A sub-triangle whose parent the candidates pass did not mark divergent
// (the host's list allows a 1% margin on the area) is written discarded.

layout(push_constant) uniform FlcSubdividePush {
    uint triangle_count;
    uint entry_count;
    uint sub_count;
    uint seed;
    int level_count;
    float s0;
    float mu;
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

layout(std430, set = 0, binding = 2) readonly buffer VertexRandomBuffer { uint items[]; } vertex_random;

// One per triangle the host may subdivide, by `first`, ascending.
struct FlcSubdivisionEntry {
    uint triangle;  // scene triangle index
    uint side;      // m: m^2 sub-triangles
    uint first;     // its first sub-triangle's index among all
};
layout(std430, set = 0, binding = 3) readonly buffer FlcSubdivisionBuffer { FlcSubdivisionEntry items[]; } entries;

// [0, triangle_count): the candidates pass's (read); [triangle_count, + sub_count): written here.
layout(std430, set = 0, binding = 4) buffer FlcCandidateBuffer { FlcCandidate items[]; } candidates;
layout(std430, set = 0, binding = 5) readonly buffer TriangleAlbedoBuffer { vec4 items[]; } triangle_albedo;
layout(std430, set = 0, binding = 6) writeonly buffer CandidateAlbedoBuffer { vec4 items[]; } candidate_albedo;


// A grid corner's stand-in for the paper's noise texel: depends on (i, j, m) only.
uint grid_random(uint i, uint j, uint m) {
    return pcg_hash(pcg_hash(i + 0x9e3779b9u * j) ^ m);
}

void main() {
    uint j = linear_thread_index();
    if (j < push.triangle_count) {
        candidate_albedo.items[j] = triangle_albedo.items[j];
        return;
    }
    uint s = j - push.triangle_count;
    if (s >= push.sub_count || push.entry_count == 0u) {
        return;
    }
    // The last entry with first <= s (binary search: ~log2 of the entry count iterations).
    uint lo = 0u, hi = push.entry_count - 1u;
    while (lo < hi) {
        uint mid = (lo + hi + 1u) / 2u;
        if (entries.items[mid].first <= s) {
            lo = mid;
        } else {
            hi = mid - 1u;
        }
    }
    FlcSubdivisionEntry e = entries.items[lo];
    FlcCandidate parent = candidates.items[e.triangle];
    FlcCandidate sub;
    sub.position = parent.position;
    sub.normal = parent.normal;
    sub.area = 0.0;
    sub.level = kFlcDiscarded;
    uint m = e.side;
    uint local = s - e.first;
    if (parent.level == kFlcDivergent && local < m * m) {
        // Row r (grid j = r) holds 2 (m - r) - 1 triangles, and rows before it m^2 - (m - r)^2, so
        // m - r = ceil(sqrt(m^2 - local)); the float root is corrected by integer checks.
        uint q = m * m - local;
        uint w = uint(ceil(sqrt(float(q))));
        while (w * w < q) ++w;
        while (w > 1u && (w - 1u) * (w - 1u) >= q) --w;
        uint r = m - w;
        uint c = local - (m * m - w * w);
        uint k = c / 2u;
        // Grid corners (i, j) of the sub-triangle, counter-clockwise like the parent's.
        uvec2 a = uvec2(k, r), b = uvec2(k + 1u, r), d = uvec2(k, r + 1u);
        if ((c & 1u) != 0u) {
            a = uvec2(k + 1u, r);
            b = uvec2(k + 1u, r + 1u);
            d = uvec2(k, r + 1u);
        }
        uint i0 = scene_index(3u * e.triangle);
        uint i1 = scene_index(3u * e.triangle + 1u);
        uint i2 = scene_index(3u * e.triangle + 2u);
        vec3 p0 = scene_vertex(i0).position;
        vec3 e1 = scene_vertex(i1).position - p0;
        vec3 e2 = scene_vertex(i2).position - p0;
        vec2 middle = vec2(a + b + d) / (3.0 * float(m));
        sub.position = p0 + middle.x * e1 + middle.y * e2;
        sub.area = parent.area / float(m * m);
        uint bits = pcg_hash(vertex_random.items[i0] ^ vertex_random.items[i1] ^ vertex_random.items[i2] ^
                             grid_random(a.x, a.y, m) ^ grid_random(b.x, b.y, m) ^ grid_random(d.x, d.y, m) ^
                             pcg_hash(push.seed));
        float u = float(bits >> 8u) * (1.0 / 16777216.0);
        sub.level = flc_level(u, sub.area, push.level_count, push.s0, push.mu);
    }
    candidates.items[j] = sub;
    candidate_albedo.items[j] = triangle_albedo.items[e.triangle];
}

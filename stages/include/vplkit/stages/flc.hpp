#pragma once
// Forward light cuts (the FLC paper, Laurent et al. 2016), the foundations: the multiscale partition's
// parameters, the VPL candidate pass (shaders/flc/flc_candidates.comp), one candidate per
// scene triangle with the level Alg. 1 draws for it, and its compaction (flc_compact.comp). The math (levels, pmf, the
// partition of unity f~^k and the area a VPL stands for) is shaders/include/vplkit/flc_partition.glsl; the light at
// the kept VPLs (flc_vpl_light.comp); the splatting raster pipeline (flc_splat_proxy.vert + flc_splat_shade.frag).
// The divergent triangles' subdivision (flc_subdivide.comp).

#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/stages/direct_emissive.hpp"
#include "vplkit/stages/direct_light.hpp"
#include "vplkit/stages/gbuffer.hpp"
#include "vplkit/stages/gbuffer_views.hpp"
#include "vplkit/steps.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace vplkit::stages {

// FlcCandidate::level beside 0..N (flc_partition.glsl's kFlcDiscarded, kFlcDivergent).
inline constexpr int32_t kFlcDiscarded = -1;
inline constexpr int32_t kFlcDivergent = -2;
// More levels than this would put S_N = S_0 mu^N beyond any useful area; a guard, not a tuning.
inline constexpr uint32_t kFlcMaxLevels = 32;

// The partition: levels 0..N (level_count = N + 1), S_k = s0 mu^k (eq. 17), influence distances
// D_k = d0 mu^(k/2) (eq. 18).
struct FlcPartition {
    uint32_t level_count = 4;
    float s0 = 0.0f;  // S_0, world units squared (flc_partition_for gives eq. 1's)
    float d0 = 0.0f;  // D_0, world units
    float mu = 2.0f;  // > 1 (the paper uses 1.4 to 5)
    // 0: S_k = s0 mu^k. Else the scene's total area, and S_k is fitted to it (flc_fitted_level_area):
    // the stratified decimation (add_flc_stratify_passes) and the light pass read it; the
    // candidates' own independent draws (add_flc_candidates_pass, add_flc_subdivide_pass) use
    // S_0 mu^k, so set it only when the stratify pass draws the levels.
    float scene_area = 0.0f;
};

// Eq. 1: D_near = 0.2 scene_radius, S_0 = 4 pi D_near^2 / n_avg (each point lit by about n_avg
// VPLs at least D_near away), and D_0 = D_near. Throws vplkit::Error naming a bad argument.
FlcPartition flc_partition_for(float scene_radius, float n_avg, uint32_t level_count, float mu);

// Throws vplkit::Error naming the first bad field: level_count outside 1..kFlcMaxLevels, s0 or d0
// not finite and positive, mu not finite and above 1, or S_N or D_N not finite.
void validate(const FlcPartition& partition);

// S~_N = 1 / (1/S_0 + ... + 1/S_N): triangles larger than this are divergent.
double flc_divergence_area(const FlcPartition& partition);

// S_k as flc_partition.glsl's flc_fitted_level_area computes it: with scene_area > 0, the scene's
// area over the whole number floor(scene_area / (s0 mu^k)) of VPLs, when that is at least 1;
// else s0 mu^k. Never below s0 mu^k.
double flc_fitted_level_area(const FlcPartition& partition, uint32_t level);

struct FlcCandidateBuffers {
    BufferView vertices;       // scene::Vertex[] (72 bytes each); read
    BufferView indices;        // uint32 x 3 per triangle; read
    BufferView vertex_random;  // uint32 per vertex (scene::Scene::vertex_random); read
    BufferView candidates;     // shaders::FlcCandidate[triangle_count]; written here
    // Read vertices and indices at their device addresses (SceneBuffers::addressed, which
    // GpuScene::addressed gives): required past maxStorageBufferRange (the pass throws otherwise).
    bool addressed = false;
};

// Adds the pass "flc candidates". `seed` picks the frame's decimation (the same seed, the same
// levels). triangle_count >= 1; throws vplkit::Error on a bad partition, or when vertex_random does
// not hold exactly one entry per vertex (a scene whose loader did not fill scene::Scene::vertex_random).
void add_flc_candidates_pass(Device& device, StepList& passes, const FlcCandidateBuffers& buffers,
                             const FlcPartition& partition, uint32_t triangle_count, uint32_t seed);

struct FlcCompactBuffers {
    BufferView candidates;           // shaders::FlcCandidate[triangle_count]; read
    BufferView counts;               // flc_count_bytes(level_count): kept, divergent, per-level counts; written here
    BufferView kept_triangles;       // uint32[triangle_count] (at most that many survive); written here
    BufferView divergent_triangles;  // uint32[triangle_count]; written here
};

// Bytes of FlcCompactBuffers::counts (shaders::FlcCountBuffer): kept, divergent, one count per level.
inline constexpr uint64_t flc_count_bytes(uint32_t level_count) {
    return shaders::FlcCountBuffer::kLevelCountsOffset +
           uint64_t(level_count) * shaders::FlcCountBuffer::kLevelCountsStride;
}

// Adds "flc counts clear" and "flc compact": the kept candidates' triangle indices and the
// divergent ones as compact lists (in no particular order), and the count per level.
void add_flc_compact_passes(Device& device, StepList& passes, const FlcCompactBuffers& buffers, uint32_t level_count,
                            uint32_t triangle_count);

struct FlcVplLightBuffers {
    BufferView candidates;       // shaders::FlcCandidate[triangle_count] (add_flc_candidates_pass); read
    BufferView counts;           // FlcCompactBuffers::counts; read
    BufferView kept_triangles;   // FlcCompactBuffers::kept_triangles; read
    BufferView triangle_albedo;  // vec4[triangle_count]: diffuse reflectance per triangle (rgb); read
    BufferView vpls;             // shaders::Vpl[triangle_count]: VPL i is kept_triangles[i]'s; written here
};

struct FlcVplLightParams {
    uint32_t emitter_samples = 4;  // area samples of the emissive triangles per VPL
    uint32_t seed = 0;             // the same seed, the same samples
};

// Adds the pass "flc vpl light": each kept VPL's flux E x rho x S_k (flc_vpl_light.comp): E the
// direct irradiance on its triangle's front side at the centroid (punctual lights and emitters,
// BVH shadow rays), rho its albedo, S_k the area a level-k VPL stands for (S_0 mu^k, or
// flc_fitted_level_area's with partition.scene_area set). The
// partition must be the candidates pass's. Throws vplkit::Error on a bad partition, zero
// emitter samples, triangle_count 0, or a buffer too small for triangle_count.
void add_flc_vpl_light_pass(Device& device, StepList& passes, const BvhBuffers& bvh, const LightBuffers& lights,
                            const EmitterBuffers& emitters, const FlcVplLightBuffers& buffers,
                            const FlcPartition& partition, uint32_t triangle_count, const FlcVplLightParams& params);

// Candidates (scene triangles + sub-triangles) in all: a 32-bit index, each flc pass one dispatch of
// 64-thread groups (folded into rows past 65,535 of them: vplkit/dispatch.glsl; 2^31 threads fold
// with every index below 2^32). The candidate buffers must also fit one storage-buffer binding:
// flc_max_candidates(device) is the smaller of the two.
inline constexpr uint64_t kFlcMaxCandidates = 1ull << 31;

// The candidates a device takes: kFlcMaxCandidates, or fewer where the FlcCandidate buffer (32 bytes
// a candidate, bound whole) would pass maxStorageBufferRange (4,194,304 on lavapipe's 2^27 bytes).
uint64_t flc_max_candidates(const Device& device);

// The divergent triangles' subdivision (the FLC paper sec. 6): which triangles are cut, into how many.
struct FlcSubdivision {
    std::vector<shaders::FlcSubdivisionEntry> entries;  // by `first`, ascending
    uint32_t sub_count = 0;                             // sub-triangles in all
};

// Every triangle of area A > 0.99 S~_N (a 1% margin over the candidates pass's float test) gets
// side m = ceil(sqrt(A / (0.99 S~_N))): m^2 sub-triangles of area A / m^2 <= 0.99 S~_N, regular.
// Throws vplkit::Error when triangle_count + sub_count would exceed max_candidates (pass
// flc_max_candidates(device); fewer VPLs per point, more levels or a larger mu), or on a bad
// partition. Non-finite areas are left alone.
FlcSubdivision flc_subdivision_for(std::span<const double> triangle_areas, const FlcPartition& partition,
                                   uint64_t max_candidates = kFlcMaxCandidates);

struct FlcSubdivideBuffers {
    BufferView vertices;          // scene::Vertex[]; read
    BufferView indices;           // uint32 x 3 per triangle; read
    BufferView vertex_random;     // uint32 per vertex; read
    BufferView entries;           // FlcSubdivision::entries (at least one entry's bytes); read
    BufferView candidates;        // FlcCandidate[triangle_count + sub_count]: the head read, the tail written
    BufferView triangle_albedo;   // vec4[triangle_count]; read
    BufferView candidate_albedo;  // vec4[triangle_count + sub_count]: the albedo per candidate; written
    bool addressed = false;       // as FlcCandidateBuffers::addressed
};

// Adds "flc subdivide" (flc_subdivide.comp), after the candidates pass: candidate triangle_count + s
// is sub-triangle s with its own level (discarded if its parent was not divergent), and
// candidate_albedo holds every candidate's albedo (a sub-triangle's is its parent's). The
// compaction and the light pass then run over triangle_count + sub_count candidates. Throws
// vplkit::Error on a bad partition, a buffer too small, or too many candidates.
void add_flc_subdivide_pass(Device& device, StepList& passes, const FlcSubdivideBuffers& buffers,
                            const FlcPartition& partition, const FlcSubdivision& subdivision, uint32_t triangle_count,
                            uint32_t seed);

// Stratified decimation (flc_stratify.comp): the levels of the regular candidates drawn again,
// each level a systematic sample along `order`, coarsest first, so that the coarse levels keep
// their expected count within one VPL in every run of the order (the finer ones within about 1%),
// and with partition.scene_area set each level its fitted count in the whole scene, while each
// candidate keeps P(t in L_k) = A / S_k exactly.
struct FlcStratifyBuffers {
    BufferView candidates;  // shaders::FlcCandidate[candidate_count] (after the subdivision); levels rewritten
    BufferView order;       // uint32[candidate_count]: every candidate index once (flc_candidate_order)
    BufferView carries;     // float[level_count]: scratch, each level's offset between dispatches
};

// Adds "flc stratify" passes (one workgroup each, 4096 / level_count chunks of 256 at most).
// `seed` picks the frame's offsets. Throws vplkit::Error on a bad partition, candidate_count 0 or
// a buffer too small.
void add_flc_stratify_passes(Device& device, StepList& passes, const FlcStratifyBuffers& buffers,
                             const FlcPartition& partition, uint32_t candidate_count, uint32_t seed);

// The indices of `points` sorted by the 30-bit Morton code of their position in the points' box
// (ties by index): a run of the result is a region of space.
std::vector<uint32_t> flc_morton_order(std::span<const glm::vec3> points);

// The stratification order of the candidates: the scene triangles in `triangle_order`, each
// followed by its sub-triangles (triangle_count + first .. + side^2 - 1) when it is subdivided.
// Every candidate index appears once.
std::vector<uint32_t> flc_candidate_order(std::span<const uint32_t> triangle_order, const FlcSubdivision& subdivision,
                                          uint32_t triangle_count);

struct FlcSplatBuffers {
    BufferView candidates;      // shaders::FlcCandidate[] (their levels); read
    BufferView counts;          // FlcCompactBuffers::counts (the kept count); read
    BufferView kept_triangles;  // FlcCompactBuffers::kept_triangles; read
    BufferView vpls;            // shaders::Vpl[vpl_capacity] (add_flc_vpl_light_pass); read
    BufferView draw_args;       // kFlcDrawArgsBytes, the indirect draw's VkDrawIndirectCommand; written here
};

inline constexpr uint64_t kFlcDrawArgsBytes = 4 * sizeof(uint32_t);
// The indirect image's format: float, so that blending adds without clamping.
inline constexpr VkFormat kFlcIndirectFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

// Interleaved sub-tiles (the FLC paper sec. 6): n x n sub-images of ceil(size / n) pixels each, VPL i
// splatted into sub-tile i mod n^2 only (its light x n^2), then untiled and blurred over n x n
// windows on the same surface. Cost of the splat's fragments / n^2; the blur's price is detail.
inline constexpr uint32_t kFlcMaxSubtiles = 8;
struct FlcSplatOptions {
    uint32_t subtiles = 1;  // n, 1..kFlcMaxSubtiles (1: off)
    bool blur = true;       // false: untiling only (each pixel its own sub-tile's estimate)
    float blur_min_cos = 0.9f;
    float blur_max_distance = 0.0f;  // world units from the tangent plane; 0: gi_similarity_distance's default
};
// The side of a sub-tile: ceil(size / subtiles).
inline uint32_t flc_subtile_side(uint32_t size, uint32_t subtiles) {
    return (size + subtiles - 1) / subtiles;
}

// Adds "flc splat args" (a compute pass: the kept count as an indirect draw) and "flc splat" (the
// raster pipeline, the FLC paper sec. 5): `indirect` (kFlcIndirectFormat, colour attachment usage) is
// cleared to 0, then every kept VPL i < min(kept, vpl_capacity) is drawn as a screen-space
// rectangle bounding its support and adds, at every G-buffer pixel x inside, its unshadowed light
// (vpl_eval.glsl) times f~^k(d(x)) with additive blending. rgb: the one-bounce indirect radiance,
// a: 0. `scene_scale` (BvhBuffers::scene_scale) sets the 1/d^2 clamp as exact_gi does. The
// partition must be the candidates pass's. `gbuffer` is read in GENERAL layout (storage images).
// Throws vplkit::Error on a bad partition, vpl_capacity 0, a buffer too small, an indirect image of
// another size or format than the G-buffer's, or a scene_scale that is not finite and positive.
// With options.subtiles > 1 the splat draws into `tiled` (kFlcIndirectFormat, subtiles x
// flc_subtile_side each way, colour attachment and storage usage) and "flc untile" writes
// `indirect` (storage usage) from it; a bad subtile count or a tiled image of another size throws.
void add_flc_splat_passes(Device& device, StepList& passes, const FlcSplatBuffers& buffers, const GbufferViews& gbuffer,
                          const ImageView& indirect, const CameraView& view, const FlcPartition& partition,
                          uint32_t vpl_capacity, float scene_scale, const FlcSplatOptions& options = {},
                          const ImageView& tiled = {});

}  // namespace vplkit::stages

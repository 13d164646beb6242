#pragma once
// Sequential Monte Carlo instant radiosity (the SMC paper, Alg. 1): a VPL set Y that persists across
// frames and moves at most M_max VPLs per update towards equal intensities on the surfaces the
// camera sees indirectly. One update (add_smc_update_passes), shaders in shaders/smc/:
//
//   smc_camera_rays        camera points X from the G-buffer, a cosine ray from each (lines 3, 5)
//   smc_validate           mailbox: a VPL whose anchor the camera still sees stays valid (line 4)
//   smc_invalid_list       the others listed in index order (a stable compaction: no atomic order)
//   smc_revalidate x2      rays from X towards V random invalid VPLs (sec. 3.2.2), each round
//   + _claims              followed by its claims: the lowest-index seer becomes the anchor
//   sort                   the ray hits by weighted-resampling key, first I = candidates (line 6)
//   smc_gather_candidates
//   smc_radiosity          path-traced radiosity of each candidate, its own seed (line 7)
//   smc_density            kNN density of the candidates among Y, k = 1 (line 8, eq. 7)
//   smc_selection_keys, sort x2, smc_select, smc_replace
//                          M_min (eq. 9), the weakest out, the strongest in (lines 9-17)
//   smc_radiosity          the VPLs that entered Y, again, from seeds of their own (line 18)
//   smc_density, smc_vpls  kNN density of Y, k by eq. 8, and the Vpl buffer to render (line 19)
//
// The decisions stay on the GPU: the host records the update and reads nothing. The VPL count
// the gathers need is counters.vpl_count (SmcCounters) after the update.
//
// Visibility: BVH rays everywhere (the kit's shadow rays), where the paper renders paraboloid
// shadow maps per VPL; the mailbox test casts one ray from the eye to each anchor.
//
// Radiosity is estimated twice per VPL: as a candidate (to choose it) and when it enters Y, from
// a seed of its own (to render it: an estimate that won the choice is biased high). A VPL keeps
// its seed for its life, so while lights and geometry stay still re-estimating a survivor (line
// 18) would give the same number: only the densities (line 19) are redone for every VPL. When
// they moved (SmcSceneChange), every survivor's radiosity is estimated again as well.

#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/stages/gbuffer.hpp"
#include "vplkit/stages/gbuffer_views.hpp"
#include "vplkit/stages/sort.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"
#include "vplkit/stages/vpl_tracing.hpp"

#include <cstdint>

namespace vplkit::stages {

struct SmcOptions {
    uint32_t budget = 2048;           // I: VPLs in Y (the SMC paper's default), 1..kSmcMaxBudget
    uint32_t max_moves = 16;          // M_max: VPLs that may leave Y per update (the SMC paper's default)
    uint32_t resample_ratio = 16;     // camera rays per candidate (the paper's 16:1), >= 1
    uint32_t radiosity_samples = 16;  // paths per radiosity estimate (the paper's 16)
    // Vertices of those paths that gather direct light (1: direct only). The SMC paper simulates three
    // bounces in all its results (sec. 5); 2 here, as instant radiosity's default (--bounces 3
    // for the paper's set-up).
    uint32_t bounces = 2;
    uint32_t visibility_tries = 16;  // V: invalid VPLs each camera point tries per round (the paper's 16)
    uint32_t visibility_rounds = 2;  // rounds of those tries per update (the paper's 2)
    float strong_quantile = 0.95f;   // eq. 9: candidates stronger than this share of Y are "strong"
    // Points that measure each VPL's area: the part of its kNN disc that is open surface nearer
    // to it than to any other VPL on its plane (its Voronoi cell, smc_density.comp),
    // 0..kSmcMaxSurfaceSamples; 0: eq. 7's whole disc over k + 1/2.
    uint32_t surface_samples = 32;
    uint32_t seed = 0;
};

// The largest budget: the kNN scan is one loop over Y per query, and lavapipe ends loops after
// 65535 iterations; k by eq. 8 stays within the shader's 32 neighbours below it too.
inline constexpr uint32_t kSmcMaxBudget = 32768;
inline constexpr uint32_t kSmcMaxNeighbours = 32;
inline constexpr uint32_t kSmcMaxSurfaceSamples = 32;  // smc_density.comp's kSmcCellSamples

// Throws vplkit::Error naming the bad option.
void validate(const SmcOptions& options);

// k for the densities Y is rendered with: max(1, floor(sqrt(I / 32))) (the SMC paper eq. 8; the text
// lost the layout of the fraction: sqrt(I) / 32 would give k = 1 at the paper's I = 2048, the k
// it uses for candidates, while the paper says the two differ; sqrt(I / 32) gives 8).
uint32_t smc_render_neighbours(uint32_t budget);

// Camera rays per update: budget x resample_ratio (Error when that passes 2^31).
uint32_t smc_pool_size(const SmcOptions& options);

// What the update reads and writes. Sizes: smc_requirements. `state`, `valid` and the first word
// of `counters` (|Y|) persist from update to update: clear them (zeros) before the first.
struct SmcBuffers {
    BufferView state;         // SmcVpl[budget]: Y
    BufferView valid;         // uint32[budget]
    BufferView invalid_list;  // uint32[budget]
    BufferView hits;          // SmcVpl[pool]: camera points and their ray hits
    BufferView pool_keys;     // uint64[pool], pool_values uint32[pool]: resampling sort
    BufferView pool_values;
    BufferView candidates;         // SmcVpl[budget]
    BufferView candidate_density;  // vec4[budget]
    BufferView vpl_density;        // vec4[budget]
    BufferView vpl_keys;           // uint64[budget], vpl_values uint32[budget]: Y by intensity
    BufferView vpl_values;
    BufferView candidate_keys;  // uint64[budget], candidate_values uint32[budget]: candidates by intensity
    BufferView candidate_values;
    BufferView moves;     // uvec2[budget]
    BufferView counters;  // SmcCounters
    BufferView vpls;      // Vpl[budget]: what the gathers read (first counters.vpl_count)
    // uint32[scene triangles]: each scene triangle's BVH slot. Needed only by an update after the
    // geometry moved (SmcSceneChange::geometry); written and read within it.
    BufferView triangle_slots;
};

struct SmcRequirements {
    uint32_t pool = 0;
    uint64_t state_bytes = 0;    // also candidates
    uint64_t word_bytes = 0;     // valid, invalid_list, vpl_values, candidate_values (uint32[budget])
    uint64_t key_bytes = 0;      // vpl_keys, candidate_keys (uint64[budget])
    uint64_t density_bytes = 0;  // vec4[budget]
    uint64_t move_bytes = 0;
    uint64_t hit_bytes = 0;
    uint64_t pool_key_bytes = 0;
    uint64_t pool_value_bytes = 0;
    uint64_t counter_bytes = 0;
    uint64_t vpl_bytes = 0;
};
SmcRequirements smc_requirements(const SmcOptions& options);

// The scene as the update reads it: the BVH (ids = scene triangles) and the VPL tracer's
// sources (emitters, their selection CDF, the diffuse reflectance per triangle).
struct SmcScene {
    BvhBuffers bvh;
    VplSourceBuffers sources;
};

// What moved in the scene since the last update (a posed frame). geometry: each VPL moves with
// its triangle (the same barycentric point; dead if the BVH lost the triangle), is checked to lie
// on open surface still (a VPL another surface now covers is dead: no light, out first) and its
// anchor's view of it is traced again; geometry or lights: every VPL's radiosity is estimated
// again (both its estimates) before the selection.
struct SmcSceneChange {
    bool geometry = false;
    bool lights = false;
};

// Adds one update of Y for the frame seen by `view` through `gbuffer` (position and geometric
// normal read). `iteration` numbers the updates (each draws new random numbers); `sorter` must
// sort at least smc_pool_size(options) pairs with key_bits >= 32. Throws vplkit::Error for bad
// options, buffers smaller than smc_requirements, or a sorter too small.
void add_smc_update_passes(Device& device, StepList& passes, const GbufferViews& gbuffer, const CameraView& view,
                           const SmcScene& scene, KeyValueSorter& sorter, const SmcBuffers& buffers,
                           const SmcOptions& options, uint32_t iteration, const SmcSceneChange& change = {});

// One kNN density pass alone (smc_density.comp), for tests: the densities of `queries` (the
// first counters.candidate_count, or with queries_are_vpls the VPLs of `state` themselves, each
// leaving itself out) among the first counters.vpl_count of `state`, with k neighbours. For the
// VPLs, surface_samples > 0 counts only neighbours on each one's plane and measures the share of
// its disc that is surface with rays through `bvh` (whose scene scale also sets the floors).
void add_smc_density_pass(Device& device, StepList& passes, const BvhBuffers& bvh, const BufferView& state,
                          const BufferView& queries, const BufferView& density, const BufferView& counters,
                          uint32_t budget, uint32_t k, bool queries_are_vpls, uint32_t surface_samples);

}  // namespace vplkit::stages

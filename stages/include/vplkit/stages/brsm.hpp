#pragma once
// VPL generation from bidirectional reflective shadow maps (BRSM; Ritschel et al. 2011, as seed
// 000 sec. 4.1 and ch. 6 use it): one-bounce VPLs placed where their light matters to the camera.
// Per light, on its RSM (stages/shadow_maps.hpp), with the camera's G-buffer:
//   "brsm contribution"  every texel's expected contribution to the image, from G-buffer surfaces
//                        around it (shaders/vpl/brsm_contribution.comp), and its flux luminance
//   "brsm filter"        edge-aware Gaussian of the contributions (brsm_filter.comp, eq. 5.3)
//   "importance mips"    mip chains of the filtered contribution and of the flux (the sums)
//   "brsm importance"    their defensive mixture, normalized (brsm_importance.comp), and its chain
//   "warp samples"       hierarchical warping of a randomized Hammersley set (importance_warp.hpp)
//   "brsm vpls"          a VPL per sample: texel position and normal, flux / (N x pmf)
//   "brsm vpl count"     the running count moves past this light's VPLs
// Several lights: each gets a share of the VPLs proportional to its power (the thesis ch. 6,
// "Multiple Lights"; brsm_vpl_shares), its VPLs after the previous light's.
//
// What the VPL set means: for each light, the mean over seeds of its VPLs' total flux is the
// flux its RSM's texels of positive importance reflect, which with defensive_fraction > 0 is
// all of its RSM's reflected flux (brsm_importance.comp). VPL flux is what the surface
// re-emits, as for instant radiosity (stages/vpl_tracing.hpp): RSM flux = base colour x
// (1 - metallic) x the light's power into the texel.
//
// The runtime allocates the buffers (vplkit/brsm_buffers.hpp: BrsmOutput, which converts to
// BrsmOutputViews; ShadowMap converts to ShadowMapViews). All lights at once (every light's map
// and buffers alive together):
//   std::vector<ShadowMap> maps = ...;            // one per light, rendered (add_shadow_map_passes)
//   auto out = vplkit::stages::BrsmOutput::create(context, maps, bounds, options);
//   vplkit::PassList passes;
//   vplkit::stages::add_brsm_passes(context, passes, gbuffer, view, maps, bvh.scene_scale, options, out);
//   passes.run(context);
//   uint32_t count = vplkit::stages::download_brsm_vpl_count(out);   // VPLs 0..count-1 of out.vpls
// One light at a time (memory for one map and its buffers, however many lights; the renderer's way):
//   auto out = BrsmOutput::create_for_lights(context, scene.lights, bounds, options);
//   for each light i:  ShadowMap map = ShadowMap::create(...);
//                      allocate_brsm_light_buffers(context, map, out.lights[i]);
//                      PassList passes; (i == 0: add_brsm_count_clear_pass(passes, out))
//                      add_shadow_map_pass(...); add_brsm_light_passes(..., map, i, ...); passes.run(context);
//                      download_brsm_light_vpl_count(out, i); out.lights[i] = {vpl_share} (frees them)

#include "vplkit/stages/device.hpp"
#include "vplkit/stages/gbuffer.hpp"
#include "vplkit/stages/gbuffer_views.hpp"
#include "vplkit/stages/shadow_maps.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

namespace vplkit::stages {

// The largest importance map the warp takes (importance_warp.hpp): a light's RSM may have at
// most this many texels along its larger side.
inline constexpr uint32_t kMaxBrsmMapSize = 4096;

struct BrsmOptions {
    uint32_t vpl_count = 4096;       // over all lights, >= the number of lights with power
    uint32_t seed = 0;               // the same seed gives the same VPLs
    uint32_t samples_per_texel = 8;  // G-buffer surfaces per pVPL, 1..1024
    // The density of distances at which G-buffer surfaces are looked for around a pVPL: flat up
    // to core_radius, 1/r^2 beyond, up to max_radius (vplkit/brsm.glsl); fractions of the scene
    // scale (Bvh::scene_scale), 0 < core_radius < max_radius. The contribution's 1/d^2 is clamped
    // at core_radius too (brsm_contribution.comp). The thesis caps the density "to 1" without a
    // unit; a core of 2% and the VPLs' own 1% clamp put Cornell-box VPLs in its creases (each
    // pVPL's few samples mostly land beside it on its own plane, where they see nothing, and
    // the rest next to the nearest crease), a 10% core spreads them over the walls near the light.
    float core_radius = 0.1f;
    float max_radius = 1.0f;
    // The edge-aware Gaussian: sigma in texels (> 0) over a (2 filter_radius + 1)^2 window
    // (filter_radius 0..8); neighbours count when their normals' dot product is above
    // similarity_min_cos (in [-1, 1)) and they lie within similarity_max_distance (fraction of
    // the scene scale, > 0): the thesis eq. 5.3. The thesis gives no values; these keep a
    // 512^2 map's texels on one wall together and split walls at creases of ~25 degrees.
    float filter_sigma = 1.5f;
    uint32_t filter_radius = 4;
    float similarity_min_cos = 0.9f;
    float similarity_max_distance = 0.02f;
    // The share of the pdf proportional to flux alone, in [0, 1] (brsm_importance.comp): 0 is
    // pure BRSM (texels the camera sees no light from get no VPL); above 0 every lit texel can
    // be chosen, which makes the set unbiased for the whole reflected flux and bounds VPL flux.
    float defensive_fraction = 0.1f;
};

// Throws vplkit::Error naming the first option out of range.
void validate(const BrsmOptions& options);

// One light's working buffers (all written and read by its passes only). One definition for views
// (BrsmLightViews, what the stages take) and owned buffers (the runtime's BrsmLightBuffers,
// vplkit/brsm_buffers.hpp): a set of buffers that convert to BufferView converts to the views.
template <class BufferT>
struct BrsmLightSet {
    uint32_t map_size = 0;      // side of the square importance map: the RSM's larger side, rounded up to 2^k
    uint32_t vpl_share = 0;     // N, the VPLs this light places (0: no pass is recorded for it)
    BufferT contribution;       // float[map_size^2]: the raw estimates
    BufferT contribution_mips;  // the filtered estimates' mip chain (importance_warp.hpp layout)
    BufferT flux_mips;          // flux luminance per texel, mip chain
    BufferT importance_mips;    // the mixture (sums to 1), mip chain
    BufferT samples;            // WarpedSample[vpl_share]
    BufferT warp_count;         // WarpCountBuffer: vpl_share, or 0 when the importance is all zero

    operator BrsmLightSet<BufferView>() const requires(!std::is_same_v<BufferT, BufferView>) {
        return {map_size, vpl_share, contribution, contribution_mips, flux_mips, importance_mips, samples, warp_count};
    }
};
using BrsmLightViews = BrsmLightSet<BufferView>;

// Bytes of each of a light's buffers for a map of map_width x map_height texels and a share of
// vpl_share VPLs (all 0 but map_size when the share is 0). Throws Error for a zero map size; a
// map_size above kMaxBrsmMapSize is the caller's to refuse.
struct BrsmLightRequirements {
    uint32_t map_size = 0;
    uint64_t contribution_bytes = 0;
    uint64_t mip_chain_bytes = 0;  // each of contribution_mips, flux_mips, importance_mips
    uint64_t samples_bytes = 0;
    uint64_t warp_count_bytes = 0;
};
BrsmLightRequirements brsm_light_requirements(uint32_t map_width, uint32_t map_height, uint32_t vpl_share);

// What the passes write: the VPLs of every light, one after the other, and their running count.
// One definition for views (BrsmOutputViews) and owned buffers (the runtime's BrsmOutput).
template <class BufferT>
struct BrsmOutputSet {
    BufferT vpls;   // Vpl[capacity]: the first `count` are valid after the passes
    BufferT count;  // VplCountBuffer (count; cut_short stays 0): cleared, then read and written
    uint32_t capacity = 0;
    std::vector<BrsmLightSet<BufferT>> lights;  // one per map

    operator BrsmOutputSet<BufferView>() const requires(!std::is_same_v<BufferT, BufferView>) {
        return {vpls, count, capacity, std::vector<BrsmLightSet<BufferView>>(lights.begin(), lights.end())};
    }
};
using BrsmOutputViews = BrsmOutputSet<BufferView>;

// "brsm count clear": the running VPL count to 0, before the first light's passes.
void add_brsm_count_clear_pass(StepList& passes, const BrsmOutputViews& output);

// The passes of light `light_index` (none when its share is 0), appending its VPLs after those
// already counted. Reads the map's position, normal and flux and the G-buffer (position,
// normal, geometric normal, albedo; GENERAL layout). Its buffers must be allocated for `map`
// (brsm_light_requirements). Throws Error otherwise, for bad options or a scene_scale that is
// not positive.
void add_brsm_light_passes(Device& device, StepList& passes, const GbufferViews& gbuffer, const CameraView& view,
                           const ShadowMapViews& map, size_t light_index, float scene_scale, const BrsmOptions& options,
                           const BrsmOutputViews& output);

// add_brsm_count_clear_pass, then add_brsm_light_passes for every map in order. `maps` must
// be rendered before (add_shadow_map_passes, in this or an earlier step list) and be the maps
// `output` was allocated for; `gbuffer` is the camera's, seen through `view`. `scene_scale` is the
// BVH's (BvhBuffers::scene_scale), which the VPL falloff clamp is relative to.
void add_brsm_passes(Device& device, StepList& passes, const GbufferViews& gbuffer, const CameraView& view,
                     std::span<const ShadowMapViews> maps, float scene_scale, const BrsmOptions& options,
                     const BrsmOutputViews& output);

}  // namespace vplkit::stages

#pragma once
// The runtime's side of BRSM VPL generation (stages/brsm.hpp): each light's share of the VPLs
// (from scene::Light powers), the buffers (owning, converting to the views the stages take),
// and the blocking reads of the counts.

#include "vplkit/buffer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_lights.hpp"
#include "vplkit/shadow_map.hpp"
#include "vplkit/stages/brsm.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace vplkit {
class Context;
}  // namespace vplkit

namespace vplkit {

// Each light's share of `vpl_count`, in proportion to its power (punctual_light_power, summed
// over RGB; directional lights over the disc of the scene's bounding sphere), rounded by largest
// remainder so the shares add up to vpl_count; every light with power gets at least one, a light
// without power none. Throws Error when no light has power or vpl_count is smaller than the
// number of lights with power.
std::vector<uint32_t> brsm_vpl_shares(std::span<const scene::Light> lights, const scene::Bounds& bounds,
                                      uint32_t vpl_count);

// One light's working buffers, owned (stages/brsm.hpp's BrsmLightSet; converts to BrsmLightViews).
using BrsmLightBuffers = stages::BrsmLightSet<Buffer>;

// The VPLs, their count and each light's buffers, owned (stages/brsm.hpp's BrsmOutputSet;
// converts to BrsmOutputViews).
struct BrsmOutput : stages::BrsmOutputSet<Buffer> {
    // Buffers for these maps (each map's light gives its share). Throws Error for bad options
    // (validate), no maps, a map too large for an importance map (4096^2), or buffers beyond the
    // device's maxStorageBufferRange.
    static BrsmOutput create(Context& context, std::span<const ShadowMap> maps, const scene::Bounds& bounds,
                             const stages::BrsmOptions& options);
    // The VPL buffer, the count and each light's share, but no light's buffers yet
    // (allocate_brsm_light_buffers). Errors as create, and no lights.
    static BrsmOutput create_for_lights(Context& context, std::span<const scene::Light> lights,
                                        const scene::Bounds& bounds, const stages::BrsmOptions& options);
};

// A light's working buffers for its map (nothing when its share is 0). Throws Error for a map
// too large (4096^2 importance map at most) or buffers beyond maxStorageBufferRange.
void allocate_brsm_light_buffers(Context& context, const ShadowMap& map, BrsmLightBuffers& light);

// add_brsm_passes over the runtime's maps.
void add_brsm_passes(stages::Device& device, StepList& passes, const stages::GbufferViews& gbuffer,
                     const stages::CameraView& view, std::span<ShadowMap> maps, float scene_scale,
                     const stages::BrsmOptions& options, const stages::BrsmOutputViews& output);

// Blocking read of output.count after a run: the VPLs placed (lights whose importance was all
// zero placed none).
uint32_t download_brsm_vpl_count(const BrsmOutput& output);

// Blocking read of the VPLs a light placed: its share, or 0 when its importance was all zero
// (its light reaches no surface, or no surface it reaches reflects), or when it had no share.
// Throws Error when the light has a share but no buffers.
uint32_t download_brsm_light_vpl_count(const BrsmOutput& output, size_t light_index);
std::vector<uint32_t> download_brsm_light_vpl_counts(const BrsmOutput& output);

}  // namespace vplkit

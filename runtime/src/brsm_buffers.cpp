#include "vplkit/brsm_buffers.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/light_power.hpp"
#include "vplkit/shaders/brsm_vpls.hpp"
#include "vplkit/shaders/warp_samples.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <numeric>
#include <string>

namespace vplkit {

namespace {

Buffer storage_buffer(Context& context, uint64_t bytes, const std::string& name) {
    if (bytes > context.info().max_storage_buffer_range) {
        throw Error("BRSM: the " + name + " buffer needs " + std::to_string(bytes) +
                    " bytes, more than this device's maxStorageBufferRange of " +
                    std::to_string(context.info().max_storage_buffer_range));
    }
    return Buffer::create(context, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, name);
}

}  // namespace

std::vector<uint32_t> brsm_vpl_shares(std::span<const scene::Light> lights, const scene::Bounds& bounds,
                                      uint32_t vpl_count) {
    const double radius = 0.5 * glm::length(glm::dvec3(bounds.extent()));
    const double disc_area = std::numbers::pi * radius * radius;
    std::vector<double> power;
    for (const scene::Light& light : lights) {
        const glm::dvec3 p = punctual_light_power(light, disc_area);
        const double sum = p.x + p.y + p.z;
        if (!std::isfinite(sum)) throw Error("BRSM: light '" + light.name + "' has a power that is not finite");
        power.push_back(sum);
    }
    const double total = std::accumulate(power.begin(), power.end(), 0.0);
    const auto lit = uint32_t(std::count_if(power.begin(), power.end(), [](double p) { return p > 0.0; }));
    if (lit == 0) throw Error("BRSM: no light has any power, so there is no light to place VPLs for");
    if (vpl_count < lit) {
        throw Error("BRSM: " + std::to_string(vpl_count) + " VPLs cannot cover the " + std::to_string(lit) +
                    " lights with power (one each at least)");
    }
    // Largest remainder of the proportional split; then every lit light left without a VPL (it
    // would lose its light entirely) takes one from the largest share.
    std::vector<uint32_t> shares(lights.size(), 0);
    std::vector<std::pair<double, size_t>> remainders;
    uint32_t given = 0;
    for (size_t i = 0; i < lights.size(); ++i) {
        if (power[i] <= 0.0) continue;
        const double exact = double(vpl_count) * (power[i] / total);
        shares[i] = std::min(vpl_count, uint32_t(std::floor(exact)));
        given += shares[i];
        remainders.push_back({exact - std::floor(exact), i});
    }
    std::stable_sort(remainders.begin(), remainders.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    for (size_t k = 0; given < vpl_count; ++k, ++given) ++shares[remainders[k % remainders.size()].second];
    for (size_t i = 0; i < lights.size(); ++i) {
        if (power[i] > 0.0 && shares[i] == 0) {
            --*std::max_element(shares.begin(), shares.end());
            shares[i] = 1;
        }
    }
    return shares;
}

BrsmOutput BrsmOutput::create_for_lights(Context& context, std::span<const scene::Light> lights,
                                         const scene::Bounds& bounds, const stages::BrsmOptions& options) {
    validate(options);
    if (lights.empty()) throw Error("BRSM: no punctual light to place VPLs for");
    const std::vector<uint32_t> shares = brsm_vpl_shares(lights, bounds, options.vpl_count);
    BrsmOutput out;
    out.capacity = options.vpl_count;
    out.vpls = storage_buffer(context, uint64_t(out.capacity) * sizeof(shaders::Vpl), "brsm vpls");
    out.count = storage_buffer(context, sizeof(shaders::VplCountBuffer), "brsm vpl count");
    for (uint32_t share : shares) {
        BrsmLightBuffers light;
        light.vpl_share = share;
        out.lights.push_back(std::move(light));
    }
    return out;
}

void allocate_brsm_light_buffers(Context& context, const ShadowMap& map, BrsmLightBuffers& light) {
    const uint32_t size = std::bit_ceil(std::max(map.width(), map.height()));
    if (size > stages::kMaxBrsmMapSize) {
        throw Error("BRSM: light '" + map.light.name + "''s shadow map is " + std::to_string(map.width()) + "x" +
                    std::to_string(map.height()) + " texels; importance maps go up to " +
                    std::to_string(stages::kMaxBrsmMapSize) +
                    "^2 (a point light's cube map is 3 x 2 faces): use smaller faces");
    }
    light.map_size = size;
    if (light.vpl_share == 0) return;
    const stages::BrsmLightRequirements needed =
        stages::brsm_light_requirements(map.width(), map.height(), light.vpl_share);
    light.contribution = storage_buffer(context, needed.contribution_bytes, "brsm contribution");
    light.contribution_mips = storage_buffer(context, needed.mip_chain_bytes, "brsm contribution mips");
    light.flux_mips = storage_buffer(context, needed.mip_chain_bytes, "brsm flux mips");
    light.importance_mips = storage_buffer(context, needed.mip_chain_bytes, "brsm importance mips");
    light.samples = storage_buffer(context, needed.samples_bytes, "brsm samples");
    light.warp_count = storage_buffer(context, needed.warp_count_bytes, "brsm warp count");
}

BrsmOutput BrsmOutput::create(Context& context, std::span<const ShadowMap> maps, const scene::Bounds& bounds,
                              const stages::BrsmOptions& options) {
    std::vector<scene::Light> lights;
    for (const ShadowMap& map : maps) lights.push_back(map.light);
    BrsmOutput out = create_for_lights(context, lights, bounds, options);
    for (size_t i = 0; i < maps.size(); ++i) allocate_brsm_light_buffers(context, maps[i], out.lights[i]);
    return out;
}

void add_brsm_passes(stages::Device& device, StepList& passes, const stages::GbufferViews& gbuffer,
                     const stages::CameraView& view, std::span<ShadowMap> maps, float scene_scale,
                     const stages::BrsmOptions& options, const stages::BrsmOutputViews& output) {
    const std::vector<stages::ShadowMapViews> views = shadow_map_views(maps);
    stages::add_brsm_passes(device, passes, gbuffer, view, std::span<const stages::ShadowMapViews>(views), scene_scale,
                            options, output);
}

uint32_t download_brsm_vpl_count(const BrsmOutput& output) {
    const auto counts = output.count.download<uint32_t>(1);
    return std::min(counts[0], output.capacity);
}

uint32_t download_brsm_light_vpl_count(const BrsmOutput& output, size_t light_index) {
    const BrsmLightBuffers& light = output.lights.at(light_index);
    if (light.vpl_share == 0) return 0;
    if (light.warp_count.handle() == VK_NULL_HANDLE) {
        throw Error("BRSM: light " + std::to_string(light_index) + " has no buffers (never allocated, or released)");
    }
    return std::min(light.warp_count.download<uint32_t>(1)[0], light.vpl_share);
}

std::vector<uint32_t> download_brsm_light_vpl_counts(const BrsmOutput& output) {
    std::vector<uint32_t> counts;
    for (size_t i = 0; i < output.lights.size(); ++i) counts.push_back(download_brsm_light_vpl_count(output, i));
    return counts;
}

}  // namespace vplkit

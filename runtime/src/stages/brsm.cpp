#include "vplkit/stages/brsm.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image.hpp"
#include "vplkit/light_power.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/brsm_contribution.hpp"
#include "vplkit/shaders/brsm_filter.hpp"
#include "vplkit/shaders/brsm_importance.hpp"
#include "vplkit/shaders/brsm_vpl_count.hpp"
#include "vplkit/shaders/brsm_vpls.hpp"
#include "vplkit/stages/gbuffer.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/stages/importance_warp.hpp"
#include "vplkit/stages/shadow_maps.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <numbers>
#include <numeric>
#include <string>

namespace vplkit::stages {

namespace {

constexpr uint32_t kMaxSamplesPerTexel = 1024;
constexpr uint32_t kMaxFilterRadius = 8;
// The largest importance map the warp takes (importance_warp.hpp).
constexpr uint32_t kMaxMapSize = 4096;

[[noreturn]] void bad_option(const std::string& what) { throw Error("BRSM: " + what); }

bool in_open_range(float v, float lo, float hi) { return std::isfinite(v) && v > lo && v < hi; }

Buffer storage_buffer(Context& context, uint64_t bytes, const std::string& name) {
    if (bytes > context.info().max_storage_buffer_range) {
        throw Error("BRSM: the " + name + " buffer needs " + std::to_string(bytes) +
                    " bytes, more than this device's maxStorageBufferRange of " +
                    std::to_string(context.info().max_storage_buffer_range));
    }
    return Buffer::create(context, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, name);
}

}  // namespace

void validate(const BrsmOptions& o) {
    if (o.vpl_count == 0) bad_option("vpl_count is 0");
    if (o.samples_per_texel == 0 || o.samples_per_texel > kMaxSamplesPerTexel) {
        bad_option("samples_per_texel " + std::to_string(o.samples_per_texel) + " is not in 1.." +
                   std::to_string(kMaxSamplesPerTexel));
    }
    if (!in_open_range(o.core_radius, 0.0f, INFINITY)) bad_option("core_radius must be a positive number");
    if (!in_open_range(o.max_radius, o.core_radius, INFINITY)) bad_option("max_radius must be above core_radius");
    if (!in_open_range(o.filter_sigma, 0.0f, INFINITY)) bad_option("filter_sigma must be a positive number");
    if (o.filter_radius > kMaxFilterRadius) {
        bad_option("filter_radius " + std::to_string(o.filter_radius) + " is above " + std::to_string(kMaxFilterRadius));
    }
    if (!std::isfinite(o.similarity_min_cos) || o.similarity_min_cos < -1.0f || o.similarity_min_cos >= 1.0f) {
        bad_option("similarity_min_cos must be in [-1, 1)");
    }
    if (!in_open_range(o.similarity_max_distance, 0.0f, INFINITY)) {
        bad_option("similarity_max_distance must be a positive number");
    }
    if (!std::isfinite(o.defensive_fraction) || o.defensive_fraction < 0.0f || o.defensive_fraction > 1.0f) {
        bad_option("defensive_fraction must be in [0, 1]");
    }
}

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
                                         const scene::Bounds& bounds, const BrsmOptions& options) {
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
    if (size > kMaxMapSize) {
        throw Error("BRSM: light '" + map.light.name + "''s shadow map is " + std::to_string(map.width()) + "x" +
                    std::to_string(map.height()) + " texels; importance maps go up to " + std::to_string(kMaxMapSize) +
                    "^2 (a point light's cube map is 3 x 2 faces): use smaller faces");
    }
    light.map_size = size;
    if (light.vpl_share == 0) return;
    const uint64_t texels = uint64_t(size) * size;
    const uint64_t chain = importance_mip_floats(size) * sizeof(float);
    light.contribution = storage_buffer(context, texels * sizeof(float), "brsm contribution");
    light.contribution_mips = storage_buffer(context, chain, "brsm contribution mips");
    light.flux_mips = storage_buffer(context, chain, "brsm flux mips");
    light.importance_mips = storage_buffer(context, chain, "brsm importance mips");
    light.samples = storage_buffer(context, uint64_t(light.vpl_share) * sizeof(shaders::WarpedSample), "brsm samples");
    light.warp_count = storage_buffer(context, sizeof(shaders::WarpCountBuffer), "brsm warp count");
}

BrsmOutput BrsmOutput::create(Context& context, std::span<const ShadowMap> maps, const scene::Bounds& bounds,
                              const BrsmOptions& options) {
    std::vector<scene::Light> lights;
    for (const ShadowMap& map : maps) lights.push_back(map.light);
    BrsmOutput out = create_for_lights(context, lights, bounds, options);
    for (size_t i = 0; i < maps.size(); ++i) allocate_brsm_light_buffers(context, maps[i], out.lights[i]);
    return out;
}

namespace {

// The passes of one light, up to and including its VPLs and the count that follows them.
void add_light_passes(Context& context, PassList& passes, GbufferImages& gbuffer, const CameraView& view,
                      ShadowMap& map, float scene_scale, const BrsmOptions& options, uint32_t seed,
                      BrsmLightBuffers& light, BrsmOutput& output) {
    const uint32_t size = light.map_size;
    const uint32_t top = uint32_t(importance_top_offset(size));

    const auto& contribution = context.pipeline<shaders::brsm_contribution::Pipeline>();
    shaders::brsm_contribution::Push contribution_push{};
    std::memcpy(&contribution_push.camera_view_projection, &view.view_projection,
                sizeof(contribution_push.camera_view_projection));
    contribution_push.map_size = size;
    contribution_push.sample_count = options.samples_per_texel;
    contribution_push.seed = seed;
    contribution_push.core_radius = options.core_radius * scene_scale;
    contribution_push.max_radius = options.max_radius * scene_scale;
    contribution_push.scene_scale = scene_scale;
    passes.add("brsm contribution",
               {Use::read(map.position), Use::read(map.normal), Use::read(map.flux), Use::read(gbuffer.position),
                Use::read(gbuffer.normal), Use::read(gbuffer.geometric_normal), Use::read(gbuffer.albedo),
                Use::write(light.contribution), Use::write(light.flux_mips)},
               [&contribution, &map, &gbuffer, &light, contribution_push](VkCommandBuffer cmd) {
                   shaders::brsm_contribution::Bindings b;
                   b.rsm_position = map.position.descriptor();
                   b.rsm_normal = map.normal.descriptor();
                   b.rsm_flux = map.flux.descriptor();
                   b.gbuffer_position = gbuffer.position.descriptor();
                   b.gbuffer_normal = gbuffer.normal.descriptor();
                   b.gbuffer_geometric_normal = gbuffer.geometric_normal.descriptor();
                   b.gbuffer_albedo = gbuffer.albedo.descriptor();
                   b.contribution = light.contribution.descriptor();
                   b.flux_luminance = light.flux_mips.descriptor();
                   contribution.dispatch(cmd, b, contribution_push, contribution_push.map_size,
                                         contribution_push.map_size);
               });

    shaders::brsm_filter::Spec filter_spec;
    filter_spec.kFilterRadius = int32_t(options.filter_radius);
    const auto& filter = context.pipeline<shaders::brsm_filter::Pipeline>(filter_spec);
    shaders::brsm_filter::Push filter_push{};
    filter_push.map_size = size;
    filter_push.sigma = options.filter_sigma;
    filter_push.min_cos = options.similarity_min_cos;
    filter_push.max_distance = options.similarity_max_distance * scene_scale;
    passes.add("brsm filter",
               {Use::read(map.position), Use::read(map.normal), Use::read(light.contribution), Use::read(light.flux_mips),
                Use::write(light.contribution_mips)},
               [&filter, &map, &light, filter_push](VkCommandBuffer cmd) {
                   shaders::brsm_filter::Bindings b;
                   b.rsm_position = map.position.descriptor();
                   b.rsm_normal = map.normal.descriptor();
                   b.contribution = light.contribution.descriptor();
                   b.flux_luminance = light.flux_mips.descriptor();
                   b.filtered = light.contribution_mips.descriptor();
                   filter.dispatch(cmd, b, filter_push, filter_push.map_size, filter_push.map_size);
               });

    add_importance_mip_levels_pass(context, passes, light.contribution_mips, size);
    add_importance_mip_levels_pass(context, passes, light.flux_mips, size);

    const auto& importance = context.pipeline<shaders::brsm_importance::Pipeline>();
    shaders::brsm_importance::Push importance_push{};
    importance_push.texel_count = size * size;
    importance_push.top_offset = top;
    importance_push.defensive_fraction = options.defensive_fraction;
    passes.add("brsm importance",
               {Use::read(light.contribution_mips), Use::read(light.flux_mips), Use::write(light.importance_mips)},
               [&importance, &light, importance_push](VkCommandBuffer cmd) {
                   shaders::brsm_importance::Bindings b;
                   b.contribution = light.contribution_mips.descriptor();
                   b.flux = light.flux_mips.descriptor();
                   b.importance = light.importance_mips.descriptor();
                   importance.dispatch(cmd, b, importance_push, importance_push.texel_count);
               });
    add_importance_mip_levels_pass(context, passes, light.importance_mips, size);
    add_warp_samples_pass(context, passes, light.importance_mips, light.samples, light.warp_count, size,
                          light.vpl_share, seed);

    const auto& vpls = context.pipeline<shaders::brsm_vpls::Pipeline>();
    shaders::brsm_vpls::Push vpls_push{};
    vpls_push.sample_count = light.vpl_share;
    vpls_push.map_size = size;
    vpls_push.capacity = output.capacity;
    passes.add("brsm vpls",
               {Use::read(map.position), Use::read(map.normal), Use::read(map.flux), Use::read(light.samples),
                Use::read(light.warp_count), Use::read(output.count), Use::write(output.vpls)},
               [&vpls, &map, &light, &output, vpls_push](VkCommandBuffer cmd) {
                   shaders::brsm_vpls::Bindings b;
                   b.rsm_position = map.position.descriptor();
                   b.rsm_normal = map.normal.descriptor();
                   b.rsm_flux = map.flux.descriptor();
                   b.samples = light.samples.descriptor();
                   b.warp = light.warp_count.descriptor();
                   b.vpl_count = output.count.descriptor();
                   b.vpls = output.vpls.descriptor();
                   vpls.dispatch(cmd, b, vpls_push, vpls_push.sample_count);
               });

    const auto& count = context.pipeline<shaders::brsm_vpl_count::Pipeline>();
    shaders::brsm_vpl_count::Push count_push{};
    count_push.sample_count = light.vpl_share;
    passes.add("brsm vpl count", {Use::read(light.warp_count), Use::read_write(output.count)},
               [&count, &light, &output, count_push](VkCommandBuffer cmd) {
                   shaders::brsm_vpl_count::Bindings b;
                   b.warp = light.warp_count.descriptor();
                   b.vpl_count = output.count.descriptor();
                   count.dispatch(cmd, b, count_push, 1);
               });
}

}  // namespace

void add_brsm_count_clear_pass(PassList& passes, BrsmOutput& output) {
    Buffer& count = output.count;
    passes.add("brsm count clear", {Use::transfer_dst(count)}, [&count](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, count.handle(), 0, sizeof(shaders::VplCountBuffer), 0u);
    });
}

void add_brsm_light_passes(Context& context, PassList& passes, GbufferImages& gbuffer, const CameraView& view,
                           ShadowMap& map, size_t light_index, float scene_scale, const BrsmOptions& options,
                           BrsmOutput& output) {
    validate(options);
    if (light_index >= output.lights.size()) {
        throw Error("BRSM: light " + std::to_string(light_index) + ", but the output was created for " +
                    std::to_string(output.lights.size()));
    }
    if (!(scene_scale > 0.0f) || !std::isfinite(scene_scale)) throw Error("BRSM: scene_scale must be positive");
    BrsmLightBuffers& light = output.lights[light_index];
    if (light.vpl_share == 0) return;
    if (std::bit_ceil(std::max(map.width(), map.height())) != light.map_size) {
        throw Error("BRSM: light " + std::to_string(light_index) +
                    "'s buffers were not allocated for this map (allocate_brsm_light_buffers)");
    }
    // Each light its own streams (the Hammersley rotation and the contribution samples would
    // otherwise repeat from light to light); light 0 keeps the seed itself.
    const uint32_t light_seed = options.seed ^ (0x9e3779b9u * uint32_t(light_index));
    add_light_passes(context, passes, gbuffer, view, map, scene_scale, options, light_seed, light, output);
}

void add_brsm_passes(Context& context, PassList& passes, GbufferImages& gbuffer, const CameraView& view,
                     std::span<ShadowMap> maps, float scene_scale, const BrsmOptions& options, BrsmOutput& output) {
    if (maps.size() != output.lights.size()) {
        throw Error("BRSM: " + std::to_string(maps.size()) + " maps, but the output was created for " +
                    std::to_string(output.lights.size()));
    }
    add_brsm_count_clear_pass(passes, output);
    for (size_t i = 0; i < maps.size(); ++i) {
        add_brsm_light_passes(context, passes, gbuffer, view, maps[i], i, scene_scale, options, output);
    }
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

}  // namespace vplkit::stages

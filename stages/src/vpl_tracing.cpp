#include "vplkit/stages/vpl_tracing.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/compact_vpls.hpp"
#include "vplkit/shaders/trace_vpls.hpp"
#include "vplkit/shaders/vpl_block_counts.hpp"
#include "vplkit/shaders/vpl_block_offsets.hpp"
#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/dispatch_groups.hpp"

#include <limits>
#include <string>

namespace vplkit::stages {

uint32_t vpl_capacity(const VplTracingOptions& options) {
    if (options.paths == 0 || options.max_bounces == 0 || options.max_bounces == std::numeric_limits<uint32_t>::max()) {
        throw Error("VPL tracing: paths and max_bounces must be at least 1, max_bounces below 2^32 - 1 (got " +
                    std::to_string(options.paths) + " and " + std::to_string(options.max_bounces) + ")");
    }
    const uint64_t capacity = uint64_t(options.paths) * options.max_bounces;
    if (capacity > std::numeric_limits<uint32_t>::max()) {
        throw Error("VPL tracing: " + std::to_string(options.paths) + " paths x " +
                    std::to_string(options.max_bounces) + " bounces is more VPLs than a 32-bit count holds");
    }
    return uint32_t(capacity);
}

// A block's VPLs are counted by one workgroup of vpl_block_counts and placed by one of compact_vpls.
static_assert(shaders::vpl_block_counts::kWorkgroupSize[0] == shaders::compact_vpls::kWorkgroupSize[0]);

uint32_t vpl_tracing_block_size() {
    return shaders::compact_vpls::kWorkgroupSize[0];
}

namespace {
uint32_t block_count(uint32_t paths) {
    return uint32_t((uint64_t(paths) + vpl_tracing_block_size() - 1) / vpl_tracing_block_size());
}
}  // namespace

VplTracingRequirements vpl_tracing_requirements(const VplTracingOptions& options) {
    VplTracingRequirements r;
    r.capacity = vpl_capacity(options);
    r.vpls_bytes = uint64_t(r.capacity) * sizeof(shaders::Vpl);
    r.bounces_bytes = uint64_t(r.capacity) * sizeof(uint32_t);
    r.count_bytes = sizeof(shaders::VplCountBuffer);
    r.path_vpls_bytes = r.vpls_bytes;
    r.path_counts_bytes = uint64_t(options.paths) * sizeof(uint32_t);
    r.block_vpls_bytes = uint64_t(block_count(options.paths)) * sizeof(uint32_t);
    return r;
}

namespace {

// Throws Error when a buffer of `output` is smaller than vpl_tracing_requirements(options) says;
// returns the capacity.
uint32_t require_buffers(const VplTracingOptions& options, const VplTracingBuffers& output) {
    const VplTracingRequirements needed = vpl_tracing_requirements(options);
    if (output.vpls.size < needed.vpls_bytes || output.bounces.size < needed.bounces_bytes ||
        output.count.size < needed.count_bytes || output.path_vpls.size < needed.path_vpls_bytes ||
        output.path_counts.size < needed.path_counts_bytes || output.block_vpls.size < needed.block_vpls_bytes) {
        throw Error("VPL tracing: the output buffers hold fewer than " + std::to_string(needed.capacity) +
                    " VPLs (paths x max_bounces), or the scratch buffers are smaller than " +
                    "vpl_tracing_requirements says");
    }
    return needed.capacity;
}

// `sources` with every empty view (a kind with no record) replaced by the albedo buffer, which
// the shader never reads in its place (it reads lights, emitters and the CDF below their counts
// only); throws Error when a buffer is smaller than its count's records.
VplSourceBuffers bound_sources(const VplSourceBuffers& sources) {
    if (sources.triangle_count == 0 || !sources.triangle_albedo) {
        throw Error("VPL tracing: the sources have no triangle albedo (triangle_count must be >= 1)");
    }
    if (sources.emitter_count != 0 && sources.emitter_count != sources.punctual_count + sources.emissive_count) {
        throw Error("VPL tracing: emitter_count must be 0 or punctual_count + emissive_count");
    }
    VplSourceBuffers bound = sources;
    auto check = [&](BufferView& view, uint64_t count, uint64_t record, const char* what) {
        if (count > 0 && (!view || view.size < count * record)) {
            throw Error("VPL tracing: the " + std::string(what) + " buffer '" + view.name + "' holds fewer than " +
                        std::to_string(count) + " records");
        }
        if (count == 0) view = sources.triangle_albedo;
    };
    check(bound.lights, sources.punctual_count, sizeof(shaders::PunctualLight), "lights");
    check(bound.emissive, sources.emissive_count, sizeof(shaders::EmitterTriangle), "emissive triangles");
    check(bound.emitter_cdf, sources.emitter_count, sizeof(float), "emitter CDF");
    check(bound.triangle_albedo, sources.triangle_count, sizeof(shaders::vec4), "triangle albedo");
    return bound;
}

}  // namespace

void add_pack_vpls_passes(Device& device, StepList& passes, const VplTracingOptions& options,
                          const VplTracingBuffers& output) {
    // The stable compaction: each path's VPLs to the VPLs of the paths before it.
    require_buffers(options, output);
    const uint32_t blocks = block_count(options.paths);
    passes.names({output.path_counts, output.block_vpls, output.count, output.path_vpls, output.vpls, output.bounces});
    {
        shaders::vpl_block_counts::Bindings b;
        b.path_vpl_counts = output.path_counts.descriptor();
        b.block_vpls = output.block_vpls.descriptor();
        shaders::vpl_block_counts::Push p{};
        p.path_count = options.paths;
        add_dispatch<shaders::vpl_block_counts::Module>(
            passes, "vpl block counts", device.pipeline<shaders::vpl_block_counts::Pipeline>(), b, p, options.paths);
    }
    {
        const auto& offsets = device.pipeline<shaders::vpl_block_offsets::Pipeline>();
        shaders::vpl_block_offsets::Bindings b;
        b.block_vpls = output.block_vpls.descriptor();
        b.vpl_count = output.count.descriptor();
        shaders::vpl_block_offsets::Push p{};
        p.block_count = blocks;
        add_dispatch<shaders::vpl_block_offsets::Module>(passes, "vpl block offsets", offsets, b, p,
                                                         offsets.workgroup_size[0]);  // one workgroup
    }
    {
        shaders::compact_vpls::Bindings b;
        b.path_vpls = output.path_vpls.descriptor();
        b.path_vpl_counts = output.path_counts.descriptor();
        b.block_vpls = output.block_vpls.descriptor();
        b.vpls = output.vpls.descriptor();
        b.vpl_bounces = output.bounces.descriptor();
        shaders::compact_vpls::Push p{};
        p.path_count = options.paths;
        p.max_bounces = options.max_bounces;
        add_dispatch<shaders::compact_vpls::Module>(
            passes, "compact vpls", device.pipeline<shaders::compact_vpls::Pipeline>(), b, p, options.paths);
    }
}

void add_trace_vpls_passes(Device& device, StepList& passes, const BvhBuffers& bvh, const VplSourceBuffers& sources,
                           const VplTracingOptions& options, const VplTracingBuffers& output) {
    const uint32_t capacity = require_buffers(options, output);
    const VplSourceBuffers bound = bound_sources(sources);
    const auto& pipeline = device.pipeline<shaders::trace_vpls::Pipeline>(bvh_spec<shaders::trace_vpls::Spec>(bvh));
    check_dispatch_groups(pipeline, "VPL tracing", options.paths);  // past 65,535 workgroups the grid is folded

    // Views by value: the caller's may be temporaries that are gone when the steps are recorded.
    const BufferView count = output.count;
    passes.add("vpl count clear", {Use::transfer_dst(count)}, [count](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, count.buffer, count.offset, sizeof(shaders::VplCountBuffer), 0u);
    });

    shaders::trace_vpls::Push push{};
    push.scene_center = {sources.scene_center.x, sources.scene_center.y, sources.scene_center.z};
    push.scene_radius = sources.scene_radius;
    push.path_count = options.paths;
    push.max_bounces = options.max_bounces;
    push.seed = options.seed;
    push.punctual_count = sources.punctual_count;
    push.emitter_count = sources.emitter_count;
    push.triangle_count = sources.triangle_count;
    push.capacity = capacity;
    // vpl_capacity refused max_bounces = 2^32 - 1: this does not wrap.
    push.step_limit = options.max_bounces + 1;
    shaders::trace_vpls::Bindings b;
    bind_bvh(b, bvh);
    b.lights = bound.lights.descriptor();
    b.emissive = bound.emissive.descriptor();
    b.emitter_cdf = bound.emitter_cdf.descriptor();
    b.albedo = bound.triangle_albedo.descriptor();
    b.path_vpls = output.path_vpls.descriptor();
    b.vpl_count = output.count.descriptor();
    b.path_vpl_counts = output.path_counts.descriptor();
    add_dispatch(passes, "trace vpls",
                 {Use::read(bvh.nodes), Use::read(bvh.triangles), Use::read(bvh.alpha), Use::read(bound.lights),
                  Use::read(bound.emissive), Use::read(bound.emitter_cdf), Use::read(bound.triangle_albedo),
                  Use::write(output.path_vpls), Use::write(output.path_counts), Use::read_write(count)},
                 pipeline, b, push, push.path_count);

    add_pack_vpls_passes(device, passes, options, output);
}

}  // namespace vplkit::stages

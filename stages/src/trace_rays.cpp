// The batch ray-query pass.

#include "vplkit/stages/trace_rays.hpp"

#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/error.hpp"
#include "vplkit/shaders/trace_closest.hpp"
#include "vplkit/shaders/trace_occlusion.hpp"
#include "vplkit/stages/dispatch_groups.hpp"

#include <string>
#include <vector>

namespace vplkit::stages {

namespace {

// The two trace shaders share their bindings but for the result buffer's name.
template <typename Pipeline, typename Bindings, typename Push, auto ResultBinding, typename Spec>
void record_trace(Device& device, StepList& passes, const char* name, std::vector<Use> uses, const Spec& spec,
                  const BvhBuffers& bvh, BufferView rays, BufferView results, uint32_t ray_count) {
    const auto& pipeline = device.pipeline<Pipeline>(spec);
    check_dispatch_groups(pipeline, name, ray_count);  // past 65,535 workgroups the grid is folded
    Bindings bindings;
    bind_bvh(bindings, bvh);
    bindings.rays = rays.descriptor();
    bindings.*ResultBinding = results.descriptor();
    Push push{};
    push.ray_count = ray_count;
    add_dispatch(passes, name, std::move(uses), pipeline, bindings, push, ray_count);
}

}  // namespace

void add_trace_rays_pass(Device& device, StepList& passes, const BvhBuffers& bvh, const BufferView& rays,
                         const BufferView& results, uint32_t ray_count, TraceMode mode) {
    const char* name = mode == TraceMode::closest_hit ? "trace closest" : "trace occlusion";
    if (ray_count == 0) {
        throw Error(std::string(name) + ": no rays");
    }
    const uint64_t result_size = mode == TraceMode::closest_hit ? sizeof(shaders::BvhHit) : sizeof(uint32_t);
    if (rays.size < uint64_t(ray_count) * sizeof(shaders::BvhRay)) {
        throw Error(std::string(name) + ": buffer '" + rays.name + "' holds fewer than " + std::to_string(ray_count) +
                    " rays");
    }
    if (results.size < uint64_t(ray_count) * result_size) {
        throw Error(std::string(name) + ": buffer '" + results.name + "' holds fewer than " +
                    std::to_string(ray_count) + " results");
    }
    // Views by value: the caller's may be temporaries (a GpuBvh or Buffer converted at the call).
    const BufferView nodes = bvh.nodes;
    const BufferView triangles = bvh.triangles;
    const BufferView alpha = bvh.alpha;
    std::vector<Use> uses = {Use::read(nodes), Use::read(triangles), Use::read(alpha), Use::read(rays),
                             Use::write(results)};
    if (mode == TraceMode::closest_hit) {
        record_trace<shaders::trace_closest::Pipeline, shaders::trace_closest::Bindings, shaders::trace_closest::Push,
                     &shaders::trace_closest::Bindings::hits>(device, passes, name, std::move(uses),
                                                              bvh_spec<shaders::trace_closest::Spec>(bvh), bvh, rays,
                                                              results, ray_count);
    } else {
        record_trace<shaders::trace_occlusion::Pipeline, shaders::trace_occlusion::Bindings,
                     shaders::trace_occlusion::Push, &shaders::trace_occlusion::Bindings::occlusion>(
            device, passes, name, std::move(uses), bvh_spec<shaders::trace_occlusion::Spec>(bvh), bvh, rays, results,
            ray_count);
    }
}

}  // namespace vplkit::stages

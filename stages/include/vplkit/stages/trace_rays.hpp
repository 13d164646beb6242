#pragma once
// The batch ray-query stage over a BVH (shaders/bvh/trace_closest.comp, trace_occlusion.comp):
// one query per ray of a buffer, against the BVH's nodes and triangles (bvh_buffers.hpp).
//   rays     BvhRay[ray_count] (read)
//   results  written: BvhHit[ray_count] or uint32_t[ray_count], by mode (below)

#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"

#include <cstdint>

namespace vplkit::stages {

enum class TraceMode {
    closest_hit,  // results: BvhHit[ray_count] (t, id, barycentrics, triangle; id kBvhNoHit on a miss)
    occlusion,    // results: uint32_t[ray_count], 1 when something lies strictly between tmin and tmax
};

// Adds the step "trace closest" or "trace occlusion": one query per BvhRay in `rays`.
// Throws Error for ray_count 0, buffers smaller than ray_count elements, or more rays than one
// dispatch can hold (64 * maxComputeWorkGroupCount[0]).
void add_trace_rays_pass(Device& device, StepList& passes, const BvhBuffers& bvh, const BufferView& rays,
                         const BufferView& results, uint32_t ray_count, TraceMode mode);

}  // namespace vplkit::stages

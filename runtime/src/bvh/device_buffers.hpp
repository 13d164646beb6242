#pragma once
// Private: the BVH's buffers as bvh.glsl reads them, for upload_bvh and GpuBvhBuild.

#include "vplkit/buffer.hpp"

#include <cstdint>
#include <span>
#include <string>

namespace vplkit {

class Context;

// A device-local buffer of `bytes` with device-address and storage usage, for the BVH's nodes or
// triangles (`what`: "nodes", "triangles"). Throws Error naming `what`, its size and the device's
// limit when it exceeds the largest buffer or allocation the device makes, or when device memory
// runs out; `context_name` starts the message ("BVH upload").
Buffer create_bvh_buffer(Context& context, uint64_t bytes, const char* what, const std::string& context_name);

// The alpha buffer, at a device address: the header (stages::bvh_header, where `nodes`,
// `triangles` and the alpha buffer itself are) over the first kBvhHeaderWords words of `records`
// (Bvh::alpha, whose word 0 is the masked subtree's root), or the header alone when `records` is
// empty. Past maxStorageBufferRange the BVH must be traced `addressed` (the caller sets it).
Buffer upload_bvh_alpha(Context& context, const Buffer& nodes, const Buffer& triangles,
                        std::span<const uint32_t> records, const std::string& context_name);

}  // namespace vplkit

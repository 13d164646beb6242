#pragma once
// The scene as the GI chain (gi_chain.hpp) reads it, from a renderer's own lights and triangles:
// the BVH (vplkit::build_bvh over the triangles, all opaque) and the VPL sources
// (renderer_vpl_sources.hpp), as host data in one block. Copy it into one storage buffer and
// take the views, as for VplSourceData:
//
//   auto scene = vplkit::stages::renderer_scene(lights, {}, {triangles, triangle_albedo});
//   // a buffer of scene.bytes() with storage usage, then:
//   scene.write(mapped);                                  // or a staging copy of the same bytes
//   const vplkit::stages::RendererSceneBuffers views = scene.views(my_buffer_view);
//   gi.add_gi_passes(steps, {views.bvh, views.sources, gbuffer}, frame);
//
// The BVH is read through its bindings, so its nodes and its triangles must each fit in the
// device's maxStorageBufferRange (2^27 bytes on every device: about a million triangles). A
// larger scene, or one with alpha-tested triangles, uploads a BvhBuffers of its own
// (bvh_buffers.hpp: `addressed`, Bvh::alpha) beside VplSourceData.

#include "vplkit/bvh.hpp"
#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit/stages/renderer_vpl_sources.hpp"
#include "vplkit/views.hpp"
#include "vplkit/stages/vpl_tracing.hpp"

#include <cstdint>
#include <span>

namespace vplkit::stages {

struct RendererSceneBuffers {
    BvhBuffers bvh;
    VplSourceBuffers sources;
};

struct RendererSceneData {
    Bvh bvh;                // built from RendererSurfaces::triangles, in their order
    VplSourceData sources;  // vpl_sources_from_renderer's

    // Bytes of the block: the BVH's nodes, its triangles, the header word bvh.glsl reads (no
    // alpha-test record) and the sources' block, each at a multiple of 256 bytes.
    uint64_t bytes() const;
    // Writes the block to `destination` (bytes() of them).
    void write(void* destination) const;
    // The views into `block`, a buffer holding write()'s bytes at block.offset (a multiple of the
    // device's minStorageBufferOffsetAlignment). Throws Error when `block` is smaller than bytes().
    RendererSceneBuffers views(const BufferView& block) const;
};

// Throws vplkit::Error as vpl_sources_from_renderer does (no triangle, a bad vertex, albedo,
// light or emitter).
RendererSceneData renderer_scene(std::span<const RendererLight> lights, std::span<const RendererEmitter> emitters,
                                 const RendererSurfaces& surfaces);

}  // namespace vplkit::stages

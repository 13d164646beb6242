// renderer_scene: the BVH and the VPL sources of a renderer's scene in one block, each part at
// a 256-byte boundary (block_layout.hpp).

#include "vplkit/stages/renderer_scene.hpp"

#include "vplkit/error.hpp"

#include "block_layout.hpp"

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

namespace vplkit::stages {
namespace {

using Layout = BlockLayout<4>;

// Nodes, triangles, the header and the sources, in that order.
Layout layout_of(const RendererSceneData& d) {
    return block_layout<4>({d.bvh.nodes.size() * sizeof(shaders::BvhNode),
                            std::max<size_t>(d.bvh.triangles.size(), 1) * sizeof(shaders::BvhTriangle),
                            kBvhHeaderWords * sizeof(uint32_t),  // word 0: the masked root, 0 for one tree
                            d.sources.bytes()});
}

}  // namespace

uint64_t RendererSceneData::bytes() const {
    return layout_of(*this).total;
}

void RendererSceneData::write(void* destination) const {
    const Layout l = layout_of(*this);
    auto* out = static_cast<uint8_t*>(destination);
    std::memset(out, 0, l.offset[3]);
    std::memcpy(out + l.offset[0], bvh.nodes.data(), l.size[0]);
    if (!bvh.triangles.empty()) std::memcpy(out + l.offset[1], bvh.triangles.data(), l.size[1]);
    sources.write(out + l.offset[3]);
}

RendererSceneBuffers RendererSceneData::views(const BufferView& block) const {
    const Layout l = layout_of(*this);
    if (!block || block.size < l.total) {
        throw Error("renderer scene: the buffer '" + block.name + "' holds " + std::to_string(block.size) +
                    " bytes, the scene needs " + std::to_string(l.total));
    }
    auto part = [&](int i, const char* name) {
        return BufferView{block.buffer, block.offset + l.offset[i], l.size[i], block.name + name};
    };
    RendererSceneBuffers out;
    out.bvh.nodes = part(0, " bvh nodes");
    out.bvh.triangles = part(1, " bvh triangles");
    out.bvh.alpha = part(2, " bvh header");
    out.bvh.node_count = uint32_t(bvh.nodes.size());
    out.bvh.triangle_count = uint32_t(bvh.triangles.size());
    out.bvh.scene_scale = bvh.scene_scale;
    out.bvh.alpha_tests = false;  // build_bvh's triangles are opaque
    out.sources = sources.views(part(3, " vpl sources"));
    return out;
}

RendererSceneData renderer_scene(std::span<const RendererLight> lights, std::span<const RendererEmitter> emitters,
                                 const RendererSurfaces& surfaces) {
    RendererSceneData d;
    d.sources = vpl_sources_from_renderer(lights, emitters, surfaces);  // checks the triangles first
    d.bvh = build_bvh(surfaces.triangles);
    return d;
}

}  // namespace vplkit::stages

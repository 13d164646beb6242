#pragma once
// What every indirect-light pass reads the same way: the G-buffer images and the BVH. Their
// generated Bindings structs (vplkit/shaders/<name>.hpp) name these bindings alike, so one
// template fills them for any of the GI shaders; the step uses and the target check are
// shared the same way. Private to the stage sources.

#include "vplkit/error.hpp"
#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit/stages/gbuffer_views.hpp"
#include "vplkit/steps.hpp"

#include <string>
#include <vector>

namespace vplkit::stages {

// The G-buffer images a GI shader reads (position, normals, albedo), as shader bindings...
template <typename Bindings>
void bind_gbuffer(Bindings& b, const GbufferViews& gbuffer) {
    b.gbuffer_position = gbuffer.position.descriptor();
    b.gbuffer_normal = gbuffer.normal.descriptor();
    b.gbuffer_geometric_normal = gbuffer.geometric_normal.descriptor();
    b.gbuffer_albedo = gbuffer.albedo.descriptor();
}

// The G-buffer's images a GI shader binds, followed by `more` (binding_uses matches views to them).
inline std::vector<ImageView> gbuffer_images(const GbufferViews& gbuffer, std::vector<ImageView> more = {}) {
    std::vector<ImageView> images = {gbuffer.position, gbuffer.normal, gbuffer.geometric_normal, gbuffer.albedo};
    images.insert(images.end(), more.begin(), more.end());
    return images;
}

// The G-buffer and BVH as step uses, followed by `more` (for steps that list their uses by hand).
inline std::vector<Use> gbuffer_uses(const GbufferViews& gbuffer, std::vector<Use> more) {
    std::vector<Use> uses = {Use::read(gbuffer.position), Use::read(gbuffer.normal),
                             Use::read(gbuffer.geometric_normal), Use::read(gbuffer.albedo)};
    uses.insert(uses.end(), more.begin(), more.end());
    return uses;
}

inline std::vector<Use> gbuffer_bvh_uses(const GbufferViews& gbuffer, const BvhBuffers& bvh, std::vector<Use> more) {
    more.insert(more.begin(), {Use::read(bvh.nodes), Use::read(bvh.triangles), Use::read(bvh.alpha)});
    return gbuffer_uses(gbuffer, std::move(more));
}

// Throws vplkit::Error "<stage>: '<image>' must be RGBA32F and of the G-buffer's size".
inline void check_gbuffer_target(const char* stage, const GbufferViews& gbuffer, const ImageView& target) {
    if (target.format != VK_FORMAT_R32G32B32A32_SFLOAT || target.width != gbuffer.width() ||
        target.height != gbuffer.height()) {
        throw Error(std::string(stage) + ": '" + target.name + "' must be RGBA32F and of the G-buffer's size");
    }
}

}  // namespace vplkit::stages

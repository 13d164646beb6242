#pragma once
// The runtime's G-buffer: images in the formats the stages read (stages/gbuffer_views.hpp),
// created with colour/depth attachment usage for the raster pass and storage usage for the
// compute stages that read it.

#include "vplkit/image.hpp"
#include "vplkit/stages/gbuffer_views.hpp"

#include <cstdint>

namespace vplkit {
class Context;
}

namespace vplkit {

struct GbufferImages {
    Image position;
    Image normal;
    Image geometric_normal;
    Image albedo;
    Image emission;
    Image depth;
    Image motion;

    // Throws vplkit::Error for a zero size.
    static GbufferImages create(Context& context, uint32_t width, uint32_t height);
    uint32_t width() const { return position.width(); }
    uint32_t height() const { return position.height(); }

    // As the stages take it; layouts stay tracked in these Images.
    operator stages::GbufferViews() { return {position, normal, geometric_normal, albedo, emission, depth, motion}; }
};

}  // namespace vplkit

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

// The images, owned (stages/gbuffer_views.hpp's GbufferSet; converts to GbufferViews, layouts
// staying tracked in these Images).
struct GbufferImages : stages::GbufferSet<Image> {
    // Throws vplkit::Error for a zero size.
    static GbufferImages create(Context& context, uint32_t width, uint32_t height);
};

}  // namespace vplkit

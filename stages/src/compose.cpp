#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/compose.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/compose.hpp"
#include "vplkit/shaders/compose_rgba16f.hpp"
#include "vplkit/shaders/compose_rgba8.hpp"

#include <string>

namespace vplkit::stages {

namespace {

// The entry point for the output format (a storage format is compiled into its shader).
template <class Module, class Pipeline>
void add_compose(Device& device, StepList& passes, const ImageView& direct, const ImageView& indirect,
                 const ImageView& composed) {
    // Views by value: the caller's may be temporaries that are gone when the steps are recorded.
    typename Module::Bindings b;
    b.direct = direct.descriptor();
    b.indirect = indirect.descriptor();
    b.composed = composed.descriptor();
    add_dispatch<Module>(passes, "compose", device.pipeline<Pipeline>(), b, {composed.width, composed.height},
                         {direct, indirect, composed});
}

}  // namespace

bool compose_supports(VkFormat format) {
    return format == VK_FORMAT_R32G32B32A32_SFLOAT || format == VK_FORMAT_R16G16B16A16_SFLOAT ||
           format == VK_FORMAT_R8G8B8A8_UNORM;
}

void add_compose_pass(Device& device, StepList& passes, const ImageView& direct, const ImageView& indirect,
                      const ImageView& composed) {
    for (const ImageView* image : {&direct, &indirect}) {
        if (image->width != composed.width || image->height != composed.height) {
            throw Error("compose: '" + image->name + "' must be of the frame's size (" +
                        std::to_string(composed.width) + "x" + std::to_string(composed.height) + ")");
        }
    }
    if (indirect.format != VK_FORMAT_R32G32B32A32_SFLOAT) {
        throw Error("compose: '" + indirect.name + "' must be RGBA32F (the kit's indirect light)");
    }
    if (!compose_supports(composed.format)) {
        throw Error("compose: '" + composed.name + "' must be RGBA32F, RGBA16F or RGBA8 UNORM");
    }
    if (direct.format != composed.format) {
        throw Error("compose: '" + direct.name + "' must be of the format of '" + composed.name + "'");
    }
    if (composed.format == VK_FORMAT_R16G16B16A16_SFLOAT) {
        add_compose<shaders::compose_rgba16f::Module, shaders::compose_rgba16f::Pipeline>(device, passes, direct,
                                                                                          indirect, composed);
    } else if (composed.format == VK_FORMAT_R8G8B8A8_UNORM) {
        add_compose<shaders::compose_rgba8::Module, shaders::compose_rgba8::Pipeline>(device, passes, direct, indirect,
                                                                                      composed);
    } else {
        add_compose<shaders::compose::Module, shaders::compose::Pipeline>(device, passes, direct, indirect, composed);
    }
}

}  // namespace vplkit::stages

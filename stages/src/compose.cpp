#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/compose.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/compose.hpp"

namespace vplkit::stages {

void add_compose_pass(Device& device, StepList& passes, const ImageView& direct, const ImageView& indirect,
                      const ImageView& composed) {
    for (const ImageView* image : {&direct, &indirect, &composed}) {
        if (image->format != VK_FORMAT_R32G32B32A32_SFLOAT || image->width != composed.width ||
            image->height != composed.height) {
            throw Error("compose: '" + image->name + "' must be RGBA32F and of the frame's size");
        }
    }
    const auto& pipeline = device.pipeline<shaders::compose::Pipeline>();
    // Views by value: the caller's may be temporaries that are gone when the steps are recorded.
    shaders::compose::Bindings b;
    b.direct = direct.descriptor();
    b.indirect = indirect.descriptor();
    b.composed = composed.descriptor();
    add_dispatch<shaders::compose::Module>(passes, "compose", pipeline, b, {composed.width, composed.height},
                                           {direct, indirect, composed});
}

}  // namespace vplkit::stages

#pragma once
// compose*.comp: composed = direct + indirect radiance, a = 1, into the caller's image format:
// `direct` and `composed` RGBA32F, RGBA16F or RGBA8 UNORM (both the same format; RGBA8 clamps
// each channel to [0, 1]), `indirect` the kit's RGBA32F. Images of one size, storage usage,
// GENERAL layout (or a view with a layout pointer, ImageView::layout, which the recording moves
// there: a colour target the raster pass left in an attachment or read-only layout). `direct`
// and `composed` may be the same image: the indirect light is then added to it in place (a
// renderer's colour target, say). A missing storage usage or a wrong layout is a validation
// error, not an Error: a view carries no usage to check.

#include "vplkit/stages/device.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"

#include <vulkan/vulkan.h>

namespace vplkit::stages {

// Whether add_compose_pass writes this format.
bool compose_supports(VkFormat format);

// Adds the pass "compose": reads `direct` and `indirect`, writes `composed`. Throws vplkit::Error
// naming the image when the sizes differ, `indirect` is not RGBA32F, `composed` is not a format
// compose_supports, or `direct` is not of `composed`'s format.
void add_compose_pass(Device& device, StepList& passes, const ImageView& direct, const ImageView& indirect,
                      const ImageView& composed);

}  // namespace vplkit::stages

#pragma once
// compose.comp: composed = direct + indirect radiance (RGBA32F images of one size, storage usage,
// GENERAL layout).

#include "vplkit/stages/device.hpp"
#include "vplkit/stages/steps.hpp"
#include "vplkit/stages/views.hpp"

namespace vplkit::stages {

// Adds the pass "compose": reads `direct` and `indirect`, writes `composed`. Throws vplkit::Error
// when the images differ in size or are not RGBA32F.
void add_compose_pass(Device& device, StepList& passes, const ImageView& direct, const ImageView& indirect,
                      const ImageView& composed);

}  // namespace vplkit::stages

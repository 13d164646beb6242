#pragma once
// compose.comp: composed = direct + indirect radiance (RGBA32F images of one size, storage usage).

namespace vplkit {
class Context;
class Image;
class PassList;
}  // namespace vplkit

namespace vplkit::stages {

// Adds the pass "compose". Throws vplkit::Error when the images differ in size or are not RGBA32F.
void add_compose_pass(Context& context, PassList& passes, Image& direct, Image& indirect, Image& composed);

}  // namespace vplkit::stages

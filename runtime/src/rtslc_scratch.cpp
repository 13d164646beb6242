#include "vplkit/rtslc_scratch.hpp"

#include "vplkit/context.hpp"

namespace vplkit {

RtslcScratch RtslcScratch::create(Context& context, uint32_t width, uint32_t height,
                                  const stages::RtslcOptions& options) {
    const stages::RtslcScratchRequirements needs = rtslc_scratch_requirements(width, height, options);
    RtslcScratch scratch;
    scratch.width = width;
    scratch.height = height;
    scratch.block_size = options.block_size;
    scratch.cut_size = options.samples_per_pixel;
    scratch.interleave = options.interleave;
    constexpr VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    scratch.cuts = Buffer::create(context, needs.cuts_bytes, storage, MemoryUse::device, "rtslc cuts");
    scratch.representatives =
        Buffer::create(context, needs.representatives_bytes, storage, MemoryUse::device, "rtslc representatives");
    if (needs.estimates) {
        scratch.estimates = Image::create(context, width, height, VK_FORMAT_R32G32B32A32_SFLOAT,
                                          VK_IMAGE_USAGE_STORAGE_BIT, "rtslc estimates");
    }
    return scratch;
}

}  // namespace vplkit

#include "vplkit/hybrid_cuts.hpp"

#include "vplkit/context.hpp"

namespace vplkit {

HybridCuts HybridCuts::create(Context& context, uint32_t width, uint32_t height, const stages::HybridOptions& options) {
    const stages::HybridCutRequirements needs = hybrid_cut_requirements(width, height, options);
    HybridCuts c;
    c.blocks_x = needs.blocks_x;
    c.blocks_y = needs.blocks_y;
    c.cut_size = needs.cut_size;
    constexpr VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    c.blocks = Buffer::create(context, needs.blocks_bytes, storage, MemoryUse::device, "hybrid blocks");
    c.cuts = Buffer::create(context, needs.cuts_bytes, storage, MemoryUse::device, "hybrid cuts");
    return c;
}

}  // namespace vplkit

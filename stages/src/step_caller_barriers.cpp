// StepList::record_with_caller_barriers: the barriers a caller without a frame graph would write
// from entry() and exit() around record(), written once here (the drop-in sample's 30 lines).

#include "vplkit/steps.hpp"

#include "vplkit/barriers.hpp"

#include <tuple>
#include <utility>
#include <vector>

namespace vplkit {
namespace {

// One dependency over every resource of `uses`; `to_steps`: the caller's commands -> the uses,
// else the uses -> the caller's commands. `layouts_of` gives an image's layout before and after.
template <typename LayoutsOf>
void record_barriers(VkCommandBuffer cmd, const std::vector<ResourceUse>& uses, bool to_steps,
                     VkPipelineStageFlags2 caller_stages, LayoutsOf layouts_of) {
    constexpr VkAccessFlags2 kCallerWrites = VK_ACCESS_2_MEMORY_WRITE_BIT;
    constexpr VkAccessFlags2 kCallerAccess = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    std::vector<VkBufferMemoryBarrier2> buffers;
    std::vector<VkImageMemoryBarrier2> images;
    for (const ResourceUse& u : uses) {
        const VkPipelineStageFlags2 src = to_steps ? caller_stages : u.stages;
        const VkPipelineStageFlags2 dst = to_steps ? u.stages : caller_stages;
        const VkAccessFlags2 src_access = to_steps ? kCallerWrites : u.access_flags;
        const VkAccessFlags2 dst_access = to_steps ? u.access_flags : kCallerAccess;
        if (u.buffer) {
            VkBufferMemoryBarrier2 b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
            b.srcStageMask = src;
            b.srcAccessMask = src_access;
            b.dstStageMask = dst;
            b.dstAccessMask = dst_access;
            b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            b.buffer = u.buffer;
            b.size = VK_WHOLE_SIZE;
            buffers.push_back(b);
        } else {
            VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
            b.srcStageMask = src;
            b.srcAccessMask = src_access;
            b.dstStageMask = dst;
            b.dstAccessMask = dst_access;
            std::tie(b.oldLayout, b.newLayout) = layouts_of(u);
            b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            b.image = u.image;
            b.subresourceRange = {u.aspect, 0, 1, 0, 1};
            images.push_back(b);
        }
    }
    pipeline_barriers(cmd, buffers, images);
}

}  // namespace

std::vector<BarrierRecord> StepList::record_with_caller_barriers(VkCommandBuffer cmd,
                                                                 VkPipelineStageFlags2 caller_stages) const {
    // Before: an image whose view carries a layout pointer moves from there to its first use's
    // layout in this barrier (so that the move waits for the caller's commands), any other is
    // in its first use's layout already.
    record_barriers(cmd, entry(), /*to_steps=*/true, caller_stages, [this](const ResourceUse& u) {
        for (const Step& step : steps_) {
            for (const Use& use : step.uses) {
                if (!use.is_image() || use.image.image != u.image) continue;
                if (!use.image.layout) return std::pair(u.layout, u.layout);
                const VkImageLayout from = *use.image.layout;
                *use.image.layout = u.layout;
                return std::pair(from, u.layout);
            }
        }
        return std::pair(u.layout, u.layout);
    });
    std::vector<BarrierRecord> inserted = record(cmd);
    record_barriers(cmd, exit(), /*to_steps=*/false, caller_stages,
                    [](const ResourceUse& u) { return std::pair(u.layout, u.layout); });
    return inserted;
}

}  // namespace vplkit

#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/tonemap.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/tonemap.hpp"

#include <cmath>
#include <string>

namespace vplkit::stages {

void add_tonemap_passes(Device& device, StepList& passes, const ImageView& hdr, const ImageView& ldr,
                        const BufferView& stats, float exposure) {
    if (!std::isfinite(exposure) || exposure <= 0.0f) {
        throw Error("tonemap: exposure must be a positive finite number, got " + std::to_string(exposure));
    }
    if (hdr.format != VK_FORMAT_R32G32B32A32_SFLOAT || ldr.format != VK_FORMAT_R8G8B8A8_UNORM) {
        throw Error("tonemap: needs an RGBA32F input and an RGBA8_UNORM output ('" + hdr.name + "' -> '" + ldr.name +
                    "')");
    }
    if (hdr.width != ldr.width || hdr.height != ldr.height) {
        throw Error("tonemap: '" + hdr.name + "' and '" + ldr.name + "' differ in size");
    }
    // Views by value: the caller's may be temporaries that are gone when the steps are recorded.
    passes.add("tonemap stats clear", {Use::transfer_dst(stats)}, [stats](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, stats.buffer, stats.offset, kTonemapStatsBytes, 0u);
    });
    const auto& pipeline = device.pipeline<shaders::tonemap::Pipeline>();
    shaders::tonemap::Bindings bindings;
    bindings.hdr = hdr.descriptor(VK_IMAGE_LAYOUT_GENERAL);
    bindings.ldr = ldr.descriptor(VK_IMAGE_LAYOUT_GENERAL);
    bindings.stats = stats.descriptor();
    shaders::tonemap::Push push{};
    push.exposure = exposure;
    add_dispatch<shaders::tonemap::Module>(passes, "tonemap", pipeline, bindings, push, {hdr.width, hdr.height},
                                           {hdr, ldr});
}

}  // namespace vplkit::stages

#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/vpl_keys.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/morton_keys.hpp"
#include "vplkit/shaders/vpl_bounds.hpp"

#include <cmath>
#include <string>

namespace vplkit::stages {

namespace {

bool finite(const shaders::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string format(const shaders::vec3& v) {
    return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + ")";
}

}  // namespace

void validate_vpls(std::span<const shaders::Vpl> vpls) {
    if (vpls.size() > kMaxKeyedVpls) {
        throw Error("VPL keys: " + std::to_string(vpls.size()) + " VPLs, but a key's 25-bit id allows at most " +
                    std::to_string(kMaxKeyedVpls));
    }
    for (size_t i = 0; i < vpls.size(); ++i) {
        if (!finite(vpls[i].position)) {
            throw Error("VPL " + std::to_string(i) + " has a non-finite position " + format(vpls[i].position));
        }
        if (!finite(vpls[i].normal)) {
            throw Error("VPL " + std::to_string(i) + " has a non-finite normal " + format(vpls[i].normal));
        }
    }
}

void add_vpl_key_passes(Device& device, StepList& passes, const VplKeyBuffers& buffers, const ElementCount& count) {
    const uint32_t capacity = count.capacity;
    if (capacity == 0 || capacity > kMaxKeyedVpls) {
        throw Error("VPL keys: count " + std::to_string(capacity) + " is outside 1.." + std::to_string(kMaxKeyedVpls));
    }
    const BufferView& vpls = buffers.vpls;
    const BufferView& bounds = buffers.bounds;
    const BufferView& keys = buffers.keys;
    const BufferView& values = buffers.values;
    passes.names({vpls, bounds, keys, values});  // report the caller's names, not the bindings'

    passes.add("vpl bounds clear", {Use::transfer_dst(bounds)}, [bounds](VkCommandBuffer cmd) {
        // An empty box: lo at the largest ordered value, hi at the smallest.
        vkCmdFillBuffer(cmd, bounds.buffer, bounds.offset + offsetof(shaders::VplBoundsBuffer, lo),
                        3 * sizeof(uint32_t), 0xffffffffu);
        vkCmdFillBuffer(cmd, bounds.buffer, bounds.offset + offsetof(shaders::VplBoundsBuffer, hi),
                        3 * sizeof(uint32_t), 0u);
    });

    const auto& bounds_pipeline = device.pipeline<shaders::vpl_bounds::Pipeline>();
    shaders::vpl_bounds::Bindings bounds_bindings;
    bounds_bindings.vpls = vpls.descriptor();
    bounds_bindings.bounds = bounds.descriptor();
    bounds_bindings.element_count_words = count.descriptor(vpls);
    shaders::vpl_bounds::Push bounds_push{};
    bounds_push.vpl_count = capacity;
    bounds_push.count_word = count.push_word();
    add_dispatch<shaders::vpl_bounds::Module>(passes, "vpl bounds", bounds_pipeline, bounds_bindings, bounds_push,
                                              capacity);

    const auto& keys_pipeline = device.pipeline<shaders::morton_keys::Pipeline>();
    shaders::morton_keys::Bindings keys_bindings;
    keys_bindings.vpls = vpls.descriptor();
    keys_bindings.bounds = bounds.descriptor();
    keys_bindings.keys = keys.descriptor();
    keys_bindings.values = values.descriptor();
    keys_bindings.element_count_words = count.descriptor(vpls);
    shaders::morton_keys::Push keys_push{};
    keys_push.vpl_count = capacity;
    keys_push.count_word = count.push_word();
    add_dispatch<shaders::morton_keys::Module>(passes, "morton keys", keys_pipeline, keys_bindings, keys_push,
                                               capacity);
}

}  // namespace vplkit::stages

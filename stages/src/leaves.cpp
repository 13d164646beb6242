#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/leaves.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/gather_leaves.hpp"

#include <string>

namespace vplkit::stages {

void add_gather_leaves_pass(Device& device, StepList& passes, const BufferView& vpls, const BufferView& sorted_values,
                            const BufferView& leaves, const ElementCount& element_count) {
    const uint32_t count = element_count.capacity;
    if (count == 0) {
        throw Error("gather leaves: no VPLs (a tree needs at least one)");
    }
    const uint32_t leaves_needed = leaf_count(count);
    if (leaves.size < uint64_t(leaves_needed) * sizeof(shaders::Vpl)) {
        throw Error("gather leaves: buffer '" + leaves.name + "' holds fewer than the " +
                    std::to_string(leaves_needed) + " leaves of " + std::to_string(count) + " VPLs");
    }
    if (vpls.size < uint64_t(count) * sizeof(shaders::Vpl) || sorted_values.size < uint64_t(count) * sizeof(uint32_t)) {
        throw Error("gather leaves: buffers '" + vpls.name + "' / '" + sorted_values.name + "' are smaller than " +
                    std::to_string(count) + " VPLs");
    }
    passes.names({vpls, sorted_values, leaves});  // report the caller's names, not "order"
    const auto& pipeline = device.pipeline<shaders::gather_leaves::Pipeline>();
    shaders::gather_leaves::Bindings bindings;
    bindings.vpls = vpls.descriptor();
    bindings.order = sorted_values.descriptor();
    bindings.leaves = leaves.descriptor();
    bindings.element_count_words = element_count.descriptor(vpls);
    shaders::gather_leaves::Push push{};
    push.count = count;
    push.leaf_count = leaves_needed;
    push.count_word = element_count.push_word();
    add_dispatch<shaders::gather_leaves::Module>(passes, "gather leaves", pipeline, bindings, push, leaves_needed);
}

}  // namespace vplkit::stages

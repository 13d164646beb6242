#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/dispatch_groups.hpp"
#include "vplkit/stages/sst.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/build_sst.hpp"

#include <cmath>
#include <string>

namespace vplkit::stages {

namespace {

void check_range(const Device& device, const BufferView& buffer, uint64_t needed, const std::string& what) {
    if (buffer.size < needed) {
        throw Error("sst: buffer '" + buffer.name + "' holds " + std::to_string(buffer.size) + " bytes; " + what +
                    " need " + std::to_string(needed));
    }
    // The shader binds whole buffers: what it needs must fit one storage-buffer descriptor.
    if (needed > device.limits().max_storage_buffer_range) {
        throw Error("sst: " + what + " need " + std::to_string(needed) +
                    " bytes, above the device's storage-buffer range of " +
                    std::to_string(device.limits().max_storage_buffer_range));
    }
}

}  // namespace

void add_sst_passes(Device& device, StepList& passes, const BufferView& leaves, const BufferView& nodes,
                    const BufferView& counters, const ElementCount& element_count, const SstOptions& options) {
    const uint32_t count = element_count.capacity;
    if (count == 0) {
        throw Error("sst: no VPLs (a tree needs at least one)");
    }
    if (count > (1u << 31)) {
        throw Error("sst: " + std::to_string(count) + " VPLs; at most 2^31 leaves fit a 32-bit index");
    }
    if (!std::isfinite(options.nu_min) || !std::isfinite(options.sigma_max) || options.sigma_max < 0.0f) {
        throw Error("sst: thresholds nu_min = " + std::to_string(options.nu_min) +
                    ", sigma_max = " + std::to_string(options.sigma_max) + " must be finite and sigma_max >= 0");
    }
    const uint32_t size = options.workgroup_size;
    if (size == 0 || size > device.limits().max_workgroup_invocations || size > device.limits().max_workgroup_size[0]) {
        throw Error("sst: workgroup size " + std::to_string(size) + " is outside 1.." +
                    std::to_string(device.limits().max_workgroup_invocations));
    }
    const uint32_t leaves_in_tree = leaf_count(count);
    const uint32_t threads = leaves_in_tree == 1 ? 1u : leaves_in_tree / 2u;
    const uint32_t node_count = sst_node_count(count);
    const uint32_t counter_count = sst_counter_count(count);
    check_range(device, leaves, uint64_t(leaves_in_tree) * sizeof(shaders::Vpl),
                "the " + std::to_string(leaves_in_tree) + " leaves of " + std::to_string(count) + " VPLs");
    check_range(device, nodes, uint64_t(node_count) * sizeof(shaders::SstNode),
                "the " + std::to_string(node_count) + " nodes of " + std::to_string(count) + " VPLs");
    check_range(device, counters, uint64_t(counter_count) * sizeof(uint32_t),
                "the " + std::to_string(counter_count) + " counters of " + std::to_string(count) + " VPLs");

    shaders::build_sst::Spec spec;
    spec.local_size_x = size;
    const auto& pipeline = device.pipeline<shaders::build_sst::Pipeline>(spec);
    check_dispatch_groups(pipeline, "sst", threads);  // past 65,535 workgroups the grid is folded

    passes.add("sst clear counters", {Use::transfer_dst(counters)}, [counters, counter_count](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, counters.buffer, counters.offset, uint64_t(counter_count) * sizeof(uint32_t), 0u);
    });

    shaders::build_sst::Push push{};
    push.count = count;
    push.leaf_count = leaves_in_tree;
    push.nu_min = options.nu_min;
    push.sigma_max = options.sigma_max;
    push.count_word = element_count.push_word();
    passes.names({leaves, nodes, counters});  // report the caller's names, not the bindings'
    shaders::build_sst::Bindings bindings;
    bindings.leaves = leaves.descriptor();
    bindings.nodes = nodes.descriptor();
    bindings.counters = counters.descriptor();
    bindings.element_count_words = element_count.descriptor(leaves);
    add_dispatch<shaders::build_sst::Module>(passes, "build sst", pipeline, bindings, push, threads);
}

}  // namespace vplkit::stages

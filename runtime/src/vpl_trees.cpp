#include "vplkit/vpl_trees.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/leaves.hpp"
#include "vplkit/stages/vpl_keys.hpp"

#include <string>

namespace vplkit {

struct VplTrees::Scratch {
    Buffer bounds;
    Buffer keys;
    Buffer values;
    Buffer sst_counters;
    stages::KeyValueSorter sorter;
};

VplTrees VplTrees::create(Context& context, uint32_t count, const VplTreeOptions& options) {
    if (count == 0 || count > stages::kMaxKeyedVpls) {
        throw Error("vpl trees: " + std::to_string(count) + " VPLs; 1.." + std::to_string(stages::kMaxKeyedVpls) +
                    " can be sorted");
    }
    constexpr VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    VplTrees trees;
    trees.count = count;
    trees.leaf_count = stages::leaf_count(count);
    trees.context_ = &context;
    trees.options_ = options;
    trees.leaves = Buffer::create(context, uint64_t(trees.leaf_count) * sizeof(shaders::Vpl), storage,
                                  MemoryUse::device, "leaves");
    trees.light_tree =
        Buffer::create(context, uint64_t(stages::light_tree_node_count(count)) * sizeof(shaders::LightTreeNode),
                       storage, MemoryUse::device, "light tree");
    trees.sst = Buffer::create(context, uint64_t(stages::sst_node_count(count)) * sizeof(shaders::SstNode), storage,
                               MemoryUse::device, "sst");
    trees.scratch_ = std::make_shared<Scratch>(
        Scratch{Buffer::create(context, stages::kVplBoundsBytes, storage, MemoryUse::device, "vpl bounds"),
                Buffer::create(context, uint64_t(count) * 8, storage, MemoryUse::device, "vpl keys"),
                Buffer::create(context, uint64_t(count) * 4, storage, MemoryUse::device, "vpl key values"),
                Buffer::create(context, uint64_t(stages::sst_counter_count(count)) * 4, storage, MemoryUse::device,
                               "sst counters"),
                stages::KeyValueSorter(context, count, options.sort)});
    return trees;
}

void VplTrees::add_build_passes(PassList& passes, const Buffer& vpls, bool build_light_tree, bool build_sst,
                                const VplTreeBuildTags& tags) {
    add_build_passes(passes, vpls, stages::ElementCount(count), build_light_tree, build_sst, tags);
}

void VplTrees::add_build_passes(PassList& passes, const Buffer& vpls, const stages::ElementCount& vpl_count,
                                bool build_light_tree, bool build_sst, const VplTreeBuildTags& tags) {
    if (vpl_count.capacity != count) {
        throw Error("vpl trees: made for " + std::to_string(count) + " VPLs, given a count of capacity " +
                    std::to_string(vpl_count.capacity));
    }
    Scratch& s = *scratch_;
    passes.set_tag(tags.sort);
    add_vpl_key_passes(*context_, passes, {vpls, s.bounds, s.keys, s.values}, vpl_count);
    s.sorter.add_pass(passes, s.keys, s.values, count);  // the padding's keys sort last
    add_gather_leaves_pass(*context_, passes, vpls, s.values, leaves, vpl_count);
    passes.set_tag(tags.light_tree);
    if (build_light_tree) add_light_tree_passes(*context_, passes, leaves, light_tree, vpl_count, options_.light_tree);
    passes.set_tag(tags.sst);
    if (build_sst) add_sst_passes(*context_, passes, leaves, sst, s.sst_counters, vpl_count, options_.sst);
    passes.set_tag(0);
}

}  // namespace vplkit

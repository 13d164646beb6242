#include "vplkit/stages/scene_light_tree.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/light_tree_scene_leaves.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/vpl_keys.hpp"

#include <string>

namespace vplkit::stages {

namespace {

[[noreturn]] void refuse(const std::string& what) {
    throw Error("scene light tree: " + what);
}

void check(const SceneLightTreeSources& sources, const SceneLightTreeScratch& scratch, const KeyValueSorter& sorter,
           const SceneLightTreeBuffers& tree) {
    const uint32_t count = sources.count;
    if (count == 0 || count > kMaxKeyedVpls) {
        refuse(std::to_string(count) + " lights; 1.." + std::to_string(kMaxKeyedVpls) + " can be keyed");
    }
    if (sources.triangle_count > count) refuse("triangle_count exceeds count");
    if (tree.count != count || tree.triangle_count != sources.triangle_count ||
        tree.leaf_count != light_tree_leaf_count(count)) {
        refuse("the tree's buffers were made for another set of lights");
    }
    if (sorter.max_count() < count) refuse("the sorter holds fewer than " + std::to_string(count) + " pairs");
    auto need = [](const BufferView& view, uint64_t bytes) {
        if (view.size < bytes)
            refuse("buffer '" + view.name + "' holds fewer than " + std::to_string(bytes) + " bytes");
    };
    need(sources.proxies, uint64_t(count) * sizeof(shaders::Vpl));
    need(sources.emitters, uint64_t(sources.triangle_count) * sizeof(shaders::EmissiveTriangle));
    need(sources.punctual, uint64_t(count - sources.triangle_count) * sizeof(shaders::PunctualLight));
    need(scratch.bounds, kVplBoundsBytes);
    need(scratch.keys, uint64_t(count) * sizeof(uint64_t));
    need(tree.leaf_lights, uint64_t(count) * sizeof(uint32_t));
    need(tree.nodes, uint64_t(light_tree_node_count(count)) * sizeof(shaders::LightTreeNode));
}

}  // namespace

void add_scene_light_tree_passes(Device& device, StepList& passes, const SceneLightTreeSources& sources,
                                 const SceneLightTreeScratch& scratch, KeyValueSorter& sorter,
                                 const SceneLightTreeBuffers& tree, const LightTreeOptions& options) {
    check(sources, scratch, sorter, tree);
    const uint32_t count = sources.count;
    // The VPL keys over the proxies: the values are the light indices, sorted with the keys.
    add_vpl_key_passes(device, passes, {sources.proxies, scratch.bounds, scratch.keys, tree.leaf_lights}, count);
    sorter.add_pass(passes, scratch.keys, tree.leaf_lights, count);

    shaders::light_tree_scene_leaves::Spec spec;
    spec.local_size_x = options.workgroup_size;
    const auto& pipeline = device.pipeline<shaders::light_tree_scene_leaves::Pipeline>(spec);
    shaders::light_tree_scene_leaves::Bindings b;
    // Report the caller's names, not the bindings' (StepList::name).
    passes.names({sources.proxies, tree.leaf_lights, sources.emitters, sources.punctual, tree.nodes});
    b.proxies = sources.proxies.descriptor();
    b.order = tree.leaf_lights.descriptor();
    b.emitters = sources.emitters.descriptor();
    b.lights = sources.punctual.descriptor();
    b.nodes = tree.nodes.descriptor();
    shaders::light_tree_scene_leaves::Push push{};
    push.count = count;
    push.leaf_count = tree.leaf_count;
    push.triangle_count = sources.triangle_count;
    add_dispatch<shaders::light_tree_scene_leaves::Module>(passes, "light tree scene leaves", pipeline, b, push,
                                                           tree.leaf_count);
    add_light_tree_levels_pass(device, passes, tree.nodes, count, options);
}

}  // namespace vplkit::stages

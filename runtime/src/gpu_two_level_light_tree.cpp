#include "vplkit/gpu_two_level_light_tree.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gpu_light_tree.hpp"
#include "vplkit/two_level_light_tree.hpp"

#include <vector>

namespace vplkit {

struct GpuTwoLevelLightTree::State {
    uint32_t top_leaf_count = 0;
    uint32_t triangle_count = 0;
    Buffer nodes;
    Buffer bottoms;
    Buffer leaf_lights;
    GpuLights punctual;
    BufferView emitters;
};

GpuTwoLevelLightTree GpuTwoLevelLightTree::create(Context& context, const scene::Scene& scene,
                                                  const GpuEmitters& emitters) {
    std::vector<uint32_t> group_first;
    const std::vector<TwoLevelLight> lights = two_level_lights(scene, group_first);
    if (lights.empty()) {
        throw Error(scene.source.string() +
                    ": the light tree needs an emissive triangle, a point or a spot light; the scene has none");
    }
    const TwoLevelLightTree tree = build_two_level_light_tree(lights, group_first);
    // The same lights in the same order as the one-level tree's (emitters, then point and spot).
    const LightTreeLights same = light_tree_lights(scene);
    if (same.proxies.size() != lights.size()) throw Error("two-level light tree: the light lists disagree");

    constexpr VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    auto upload = [&](const auto& items, const char* name) {
        auto buffer =
            Buffer::create(context, uint64_t(items.size()) * sizeof(items[0]), storage, MemoryUse::device, name);
        buffer.upload(items);
        return buffer;
    };
    GpuTwoLevelLightTree out;
    out.count_ = uint32_t(lights.size());
    out.mesh_lights_ = uint32_t(tree.top_leaves.size());
    out.state_ = std::make_shared<State>(State{tree.top_leaf_count, same.triangle_count,
                                               upload(tree.nodes, "two-level light tree nodes"),
                                               upload(tree.top_leaves, "two-level light tree bottoms"),
                                               upload(tree.leaf_lights, "two-level light tree leaf lights"),
                                               upload_lights(context, same.punctual), emitters.triangles});
    return out;
}

stages::TwoLevelLightTreeBuffers GpuTwoLevelLightTree::buffers() const {
    const State& s = *state_;
    return {s.top_leaf_count, s.triangle_count, s.nodes, s.bottoms, s.leaf_lights, s.emitters, s.punctual.lights};
}

}  // namespace vplkit

#include "vplkit/gpu_light_tree.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/light_power.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/vpl_keys.hpp"

#include <glm/geometric.hpp>

#include <cmath>
#include <string>

namespace vplkit {

namespace {

shaders::vec3 to_shader(glm::vec3 v) {
    return {v.x, v.y, v.z};
}

bool finite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

LightTreeLights light_tree_lights(const scene::Scene& scene) {
    LightTreeLights out;
    for (const EmitterTriangle& e : emitter_triangles(scene)) {
        const glm::vec3 a{e.triangle.v0.x, e.triangle.v0.y, e.triangle.v0.z};
        const glm::vec3 b{e.triangle.v1.x, e.triangle.v1.y, e.triangle.v1.z};
        const glm::vec3 c{e.triangle.v2.x, e.triangle.v2.y, e.triangle.v2.z};
        glm::vec3 normal = glm::normalize(glm::cross(b - a, c - a));
        if (!finite(normal)) normal = {0.0f, 0.0f, 1.0f};  // a sliver: the key's normal code only orders it
        shaders::Vpl proxy{};
        proxy.position = to_shader((a + b + c) / 3.0f);
        proxy.normal = to_shader(normal);
        proxy.flux = to_shader(glm::vec3(e.power));
        out.proxies.push_back(proxy);
    }
    out.triangle_count = uint32_t(out.proxies.size());
    for (const scene::Light& light : scene.lights) {
        if (light.type == scene::LightType::directional) continue;
        shaders::Vpl proxy{};
        proxy.position = to_shader(light.position);
        proxy.normal = to_shader(light.type == scene::LightType::spot ? light.direction : glm::vec3(0, 0, 1));
        proxy.flux = to_shader(glm::vec3(punctual_light_power(light, 0.0)));
        out.proxies.push_back(proxy);
        out.punctual.push_back(light);
    }
    return out;
}

std::vector<scene::Light> directional_lights(const scene::Scene& scene) {
    std::vector<scene::Light> out;
    for (const scene::Light& light : scene.lights) {
        if (light.type == scene::LightType::directional) out.push_back(light);
    }
    return out;
}

struct GpuLightTree::State {
    Buffer proxies;
    GpuLights punctual;
    BufferView emitters;
    Buffer bounds;
    Buffer keys;
    Buffer leaf_lights;
    Buffer nodes;
    stages::KeyValueSorter sorter;
};

GpuLightTree GpuLightTree::create(Context& context, const scene::Scene& scene, const GpuEmitters& emitters) {
    LightTreeLights lights = light_tree_lights(scene);
    const uint32_t count = uint32_t(lights.proxies.size());
    if (count == 0) {
        throw Error(scene.source.string() +
                    ": the light tree needs an emissive triangle, a point or a spot light; the scene has none");
    }
    if (count > stages::kMaxKeyedVpls) {
        throw Error(scene.source.string() + ": " + std::to_string(count) + " lights; the light tree keys at most " +
                    std::to_string(stages::kMaxKeyedVpls));
    }
    constexpr VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    GpuLightTree tree;
    tree.count_ = count;
    tree.triangle_count_ = lights.triangle_count;
    auto proxies = Buffer::create(context, uint64_t(count) * sizeof(shaders::Vpl), storage, MemoryUse::device,
                                  "light tree proxies");
    proxies.upload(lights.proxies);
    tree.state_ = std::make_shared<State>(
        State{std::move(proxies), upload_lights(context, lights.punctual), emitters.triangles,
              Buffer::create(context, stages::kVplBoundsBytes, storage, MemoryUse::device, "light tree bounds"),
              Buffer::create(context, uint64_t(count) * 8, storage, MemoryUse::device, "light tree keys"),
              Buffer::create(context, uint64_t(count) * 4, storage, MemoryUse::device, "light tree leaf lights"),
              Buffer::create(context, uint64_t(stages::light_tree_node_count(count)) * sizeof(shaders::LightTreeNode),
                             storage, MemoryUse::device, "light tree over lights"),
              stages::KeyValueSorter(context, count)});
    return tree;
}

void GpuLightTree::add_build_passes(Context& context, PassList& passes) {
    State& s = *state_;
    const stages::SceneLightTreeSources sources{count_, triangle_count_, s.proxies, s.emitters, s.punctual.lights};
    add_scene_light_tree_passes(context, passes, sources, {s.bounds, s.keys}, s.sorter, buffers());
}

stages::SceneLightTreeBuffers GpuLightTree::buffers() const {
    const State& s = *state_;
    return {
        count_,           stages::light_tree_leaf_count(count_), triangle_count_, s.nodes, s.leaf_lights, s.emitters,
        s.punctual.lights};
}

const Buffer& GpuLightTree::nodes() const {
    return state_->nodes;
}

const Buffer& GpuLightTree::leaf_lights() const {
    return state_->leaf_lights;
}

}  // namespace vplkit

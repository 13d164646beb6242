#pragma once
// The perfect light tree over a scene's own lights (the RTSLC paper sec. 3.1: one tree over emissive
// triangles and point and spot lights), built by the VPL tree's passes: the keys (vpl_keys.hpp:
// Morton code of each light's proxy position, normal code, id), the key sort (sort.hpp), then
// tree/light_tree_scene_leaves.comp for the leaf level and light_tree_levels.comp for the rest
// (light_tree.hpp: add_light_tree_levels_pass). Directional lights have no position and are
// not in it (direct_light.comp adds them).
//
// A light's leaf: box = its extent (a triangle's three corners, a point or spot light's
// position), intensity = light_tree_intensity(RGB power). Orientation is not in the node
// (the RTSLC paper sec. 4: 32-byte nodes without bounding cones); light_tree_scene_leaves.comp says why
// that costs variance and not bias. Leaf i holds light leaf_lights[i] (the sort's values).

#include "vplkit/stages/device.hpp"
#include "vplkit/stages/light_tree.hpp"
#include "vplkit/stages/sort.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"

#include <cstdint>

namespace vplkit::stages {

// The lights of the tree, `count` of them: lights [0, triangle_count) are entries of `emitters`
// (EmissiveTriangle[], emitters.glsl), lights [triangle_count, count) entries of `punctual`
// (PunctualLight[], lights.glsl: point and spot only) at i - triangle_count.
struct SceneLightTreeSources {
    uint32_t count = 0;
    uint32_t triangle_count = 0;
    // Vpl[count], one per light: position = a triangle's centroid or the light's position (what
    // the Morton key quantizes), normal = the triangle's (a point light's: any unit vector),
    // flux = the light's RGB power (watts: radiance x area x pi x sides; 4 pi I; a spot's cone
    // integral). vplkit/gpu_light_tree.hpp fills it from a scene.
    BufferView proxies;
    BufferView emitters;
    BufferView punctual;
};

struct SceneLightTreeBuffers {
    uint32_t count = 0;       // lights in the tree
    uint32_t leaf_count = 0;  // light_tree_leaf_count(count)
    uint32_t triangle_count = 0;
    BufferView nodes;        // LightTreeNode[light_tree_node_count(count)]
    BufferView leaf_lights;  // uint32[count]: leaf i's light (the key sort's values, sorted)
    BufferView emitters;     // as SceneLightTreeSources
    BufferView punctual;
};

// The key scratch of the build: bounds (kVplBoundsBytes) and keys (uint64[count]).
struct SceneLightTreeScratch {
    BufferView bounds;
    BufferView keys;
};

// Adds the passes "vpl bounds clear", "vpl bounds", "morton keys" (over the proxies), the sort
// (sorter.add_pass: "sort"), "light tree scene leaves" and "light tree levels". The tree's
// leaf_lights are written by the keys pass and sorted in place. Throws vplkit::Error for no
// lights, more than kMaxKeyedVpls, a sorter for fewer, or buffers too small.
void add_scene_light_tree_passes(Device& device, StepList& passes, const SceneLightTreeSources& sources,
                                 const SceneLightTreeScratch& scratch, KeyValueSorter& sorter,
                                 const SceneLightTreeBuffers& tree, const LightTreeOptions& options = {});

}  // namespace vplkit::stages

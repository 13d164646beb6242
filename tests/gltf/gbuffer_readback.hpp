#pragma once
// The G-buffer of a loaded scene, read back for the gltf tests: world positions (w = 1 where a
// surface was drawn) and albedo (RGBA16F unpacked), pixel (x, y) at index y * width + x.

#include "vplkit/camera_view.hpp"
#include "vplkit/context.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/gpu_scene.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit_test/context.hpp"

#include <glm/gtc/packing.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

namespace gltf_features {

struct GbufferReadback {
    uint32_t width = 0, height = 0;
    std::vector<glm::vec4> position;
    std::vector<glm::vec3> albedo;
};

inline GbufferReadback read_gbuffer(const vplkit::scene::Scene& scene, uint32_t width, uint32_t height) {
    auto& ctx = vplkit::test::context();
    auto gpu = vplkit::GpuScene::create(ctx, scene);
    auto images = vplkit::GbufferImages::create(ctx, width, height);
    vplkit::PassList passes("gltf feature G-buffer");
    vplkit::stages::add_gbuffer_pass(ctx, passes, gpu, vplkit::camera_view(scene.camera(), width, height), images);
    passes.run(ctx);
    GbufferReadback out;
    out.width = width;
    out.height = height;
    out.position = images.position.download<glm::vec4>();
    const auto half = images.albedo.download<uint16_t>();
    for (size_t i = 0; i < out.position.size(); ++i) {
        out.albedo.emplace_back(glm::unpackHalf1x16(half[4 * i]), glm::unpackHalf1x16(half[4 * i + 1]),
                                glm::unpackHalf1x16(half[4 * i + 2]));
    }
    return out;
}

}  // namespace gltf_features

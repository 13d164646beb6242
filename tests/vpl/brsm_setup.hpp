#pragma once
// The BRSM tests' harness (test_brsm.cpp, test_brsm_vpls.cpp): an open box with point and spot
// lights (or a floor under a sun), drawn into a G-buffer and one RSM per light, the BRSM passes run
// on them, and the check of each light's mean VPL flux over seeds.

#include "brsm_reference.hpp"
#include "raster_test_scenes.hpp"

#include "vplkit/brsm_buffers.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/camera_view.hpp"
#include "vplkit/context.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/gpu_scene.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/shadow_map.hpp"
#include "vplkit_test/context.hpp"

#include <glm/vec3.hpp>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace vplkit::brsm_test {

namespace ref = vplkit::reference;
using vplkit::BrsmOutput;
using vplkit::ShadowMap;
using vplkit::scene::Light;
using vplkit::scene::LightType;
using vplkit::scene::Scene;
using vplkit::stages::BrsmOptions;

// The box [-1, 1] x [0, 2] x [-1, 1] without its front (z = 1) face, every face turned inwards,
// coordinates times `scale`; the left wall reddish, the right one greenish, a grey metal-free rest
// (the ceiling half metallic, so (1 - metallic) enters the contribution).
Scene open_box(float scale = 1.0f);
Light point_light(glm::vec3 position, float intensity);
Light spot_light(glm::vec3 position, glm::vec3 direction, float intensity);
Light sun(glm::vec3 direction, float intensity);

// A scene drawn into a G-buffer and one RSM per light, ready for the BRSM passes.
class Setup {
public:
    Setup(Scene scene, const vplkit::scene::Camera& camera, uint32_t rsm_resolution, uint32_t width = 64,
          uint32_t height = 48)
        : scene_(std::move(scene)),
          gpu_(vplkit::GpuScene::create(ctx(), scene_)),
          gbuffer_(vplkit::GbufferImages::create(ctx(), width, height)),
          view_(vplkit::camera_view(camera, width, height)),
          scene_scale_(vplkit::build_bvh(vplkit::scene::triangle_positions(scene_)).scene_scale) {
        for (const Light& light : scene_.lights) {
            maps_.push_back(ShadowMap::create(ctx(), light, gpu_.bounds(), rsm_resolution));
        }
        vplkit::PassList passes("brsm test raster");
        vplkit::stages::add_gbuffer_pass(ctx(), passes, gpu_, view_, gbuffer_);
        vplkit::add_shadow_map_passes(ctx(), passes, gpu_, maps_);
        passes.run(ctx());
    }

    static vplkit::Context& ctx() { return vplkit::test::context(); }

    BrsmOutput run(const BrsmOptions& options) {
        BrsmOutput out = BrsmOutput::create(ctx(), maps_, gpu_.bounds(), options);
        vplkit::PassList passes("brsm test");
        vplkit::add_brsm_passes(ctx(), passes, gbuffer_, view_, maps_, scene_scale_, options, out);
        passes.run(ctx());
        return out;
    }

    std::vector<vplkit::shaders::Vpl> vpls(const BrsmOutput& out) {
        const uint32_t count = vplkit::download_brsm_vpl_count(out);
        return count ? out.vpls.download<vplkit::shaders::Vpl>(count) : std::vector<vplkit::shaders::Vpl>{};
    }

    ref::Rsm rsm(size_t light) {
        ShadowMap& m = maps_[light];
        return {read(m.position), read(m.normal), read(m.flux)};
    }
    ref::Gbuffer gbuffer() {
        return {read(gbuffer_.position), read(gbuffer_.normal), read(gbuffer_.geometric_normal), read(gbuffer_.albedo)};
    }
    // Sum of the RSM's flux over its texels, per channel, optionally only where `keep` holds.
    glm::dvec3 rsm_flux_sum(size_t light, const std::vector<float>* importance = nullptr) {
        const ref::Rsm r = rsm(light);
        const uint32_t size = std::bit_ceil(std::max(r.flux.width, r.flux.height));
        glm::dvec3 sum(0.0);
        for (uint32_t y = 0; y < r.flux.height; ++y) {
            for (uint32_t x = 0; x < r.flux.width; ++x) {
                if (r.position.at(x, y).w <= 0.5f) continue;
                if (importance && !((*importance)[size_t(y) * size + x] > 0.0f)) continue;
                sum += glm::dvec3(r.flux.at(x, y));
            }
        }
        return sum;
    }

    const Scene& scene() const { return scene_; }
    const vplkit::stages::CameraView& view() const { return view_; }
    vplkit::GbufferImages& gbuffer_images() { return gbuffer_; }
    float scene_scale() const { return scene_scale_; }
    std::vector<ShadowMap>& maps() { return maps_; }

private:
    static ref::Rgba read(vplkit::Image& image) {
        return {image.width(), image.height(), raster_test::download_rgba(image)};
    }

    Scene scene_;
    vplkit::GpuScene gpu_;
    vplkit::GbufferImages gbuffer_;
    vplkit::stages::CameraView view_;
    float scene_scale_;
    std::vector<ShadowMap> maps_;
};

vplkit::scene::Camera camera(glm::vec3 eye, glm::vec3 target, glm::vec3 up, float scale);
vplkit::scene::Camera box_camera(float scale = 1.0f);
Scene box_with(std::vector<Light> lights, float scale = 1.0f);
std::vector<float> level0(const vplkit::Buffer& mips, uint32_t size);

// mean over seeds of the total flux of each light's VPLs against `expected`, per channel.
void check_mean_flux(Setup& setup, BrsmOptions options, uint32_t seeds, const std::vector<glm::dvec3>& expected);
BrsmOptions small_options(uint32_t vpls);

}  // namespace vplkit::brsm_test

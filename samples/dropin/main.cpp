// vplkit drop-in sample: one-bounce indirect light from the kit's hybrid GI stage inside a
// renderer that owns everything else. The "renderer" (plain_vulkan.hpp) creates the instance,
// device, memory and command buffer; vplkit only records its stages into that command buffer:
//
//   VPLs -> morton keys -> radix sort -> gather leaves -> SST build -> hybrid GI -> indirect image
//
// The scene: a grey Lambertian floor (y = 0, x and z in [-1, 1]) seen from above, lit by VPLs
// hovering over it and facing down. The check: the image's mean indirect radiance against a CPU
// sum over every VPL of the same formula (shaders/include/vplkit/vpl_eval.glsl), within 5%.
// Nothing occludes a VPL from the floor, so that sum is exact; hybrid's estimate is noisy and
// slightly biased per pixel (substitutes, blended cuts), the image mean is what must agree.
// Prints one line "dropin: ... ok" and exits 0 when the check holds.

#include "plain_vulkan.hpp"

#include "vplkit/bvh.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/stages/gbuffer_views.hpp"
#include "vplkit/stages/gi_counters.hpp"
#include "vplkit/stages/hybrid_gi.hpp"
#include "vplkit/stages/leaves.hpp"
#include "vplkit/stages/radix_sort.hpp"
#include "vplkit/stages/sst.hpp"
#include "vplkit/stages/steps.hpp"
#include "vplkit/stages/vpl_keys.hpp"

#include <glm/glm.hpp>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <random>
#include <vector>

namespace {

constexpr uint32_t kSize = 48;  // image width and height
constexpr uint32_t kVplCount = 500;
constexpr float kAlbedo = 0.8f;
constexpr double kPi = 3.14159265358979;

struct Scene {
    std::vector<glm::vec4> position, normal, geometric_normal;  // RGBA32F G-buffer texels
    std::vector<uint16_t> albedo;                               // RGBA16F
    std::vector<vplkit::shaders::Vpl> vpls;
    std::vector<glm::vec3> floor;  // two triangles, for the BVH the shadow rays traverse
};

uint16_t half(float f) {  // positive normal floats and 0 only: all this G-buffer holds
    if (f == 0.0f) return 0;
    uint32_t bits;
    std::memcpy(&bits, &f, 4);
    return uint16_t(((bits >> 23) - 112) << 10 | (bits >> 13 & 0x3ff));
}

Scene make_scene() {
    Scene s;
    for (uint32_t y = 0; y < kSize; ++y) {
        for (uint32_t x = 0; x < kSize; ++x) {
            const float px = -1.0f + 2.0f * (x + 0.5f) / kSize;
            const float pz = -1.0f + 2.0f * (y + 0.5f) / kSize;
            s.position.push_back({px, 0.0f, pz, 1.0f});              // w = 1: a surface was drawn
            s.normal.push_back({0.0f, 1.0f, 0.0f, -1.0f});           // w = roughness; < 0: pure Lambert
            s.geometric_normal.push_back({0.0f, 1.0f, 0.0f, 0.0f});  // w = metallic
            for (float c : {kAlbedo, kAlbedo, kAlbedo, 1.0f}) s.albedo.push_back(half(c));
        }
    }
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (uint32_t i = 0; i < kVplCount; ++i) {
        vplkit::shaders::Vpl v{};
        v.position = {-1.2f + 2.4f * u(rng), 0.3f + 0.6f * u(rng), -1.2f + 2.4f * u(rng)};
        const glm::vec3 n = glm::normalize(glm::vec3(u(rng) - 0.5f, -1.5f, u(rng) - 0.5f));
        v.normal = {n.x, n.y, n.z};
        v.flux = {0.02f + 0.03f * u(rng), 0.02f + 0.02f * u(rng), 0.01f + 0.03f * u(rng)};
        s.vpls.push_back(v);
    }
    s.floor = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
    return s;
}

// The mean over the image of sum_i albedo/pi * flux_i * cos_y cos_x / max(d^2, d_min^2) / pi.
glm::dvec3 reference_mean(const Scene& s, float scene_scale) {
    const double d_min = 0.01 * scene_scale;  // kVplMinDistanceFraction in vpl_eval.glsl
    glm::dvec3 sum(0.0);
    for (const glm::vec4& p : s.position) {
        for (const auto& v : s.vpls) {
            const glm::dvec3 to = glm::dvec3(v.position.x, v.position.y, v.position.z) - glm::dvec3(p);
            const double d2 = glm::dot(to, to);
            const glm::dvec3 wi = to / std::sqrt(d2);
            const double cos_x = wi.y;  // the floor's normal is +y
            const double cos_y = -glm::dot(glm::dvec3(v.normal.x, v.normal.y, v.normal.z), wi);
            if (cos_x <= 0.0 || cos_y <= 0.0) continue;
            sum += double(kAlbedo) / kPi * glm::dvec3(v.flux.x, v.flux.y, v.flux.z) * cos_x * cos_y /
                   std::max(d2, d_min * d_min) / kPi;
        }
    }
    return sum / double(s.position.size());
}

vplkit::BufferView view(const dropin::HostBuffer& b, const char* name) {
    return {b.buffer, 0, b.size, name};
}
vplkit::ImageView view(const dropin::StorageImage& i, const char* name) {
    return {i.image, i.view, i.format, i.width, i.height, name};  // no layout pointer: it is GENERAL throughout
}

}  // namespace

int main() {
    dropin::Gpu gpu;
    try {
        gpu = dropin::Gpu::create(/*validation=*/true);
        const Scene scene = make_scene();
        const vplkit::Bvh bvh = vplkit::build_bvh(scene.floor);

        // The kit's view of the device: pipelines are created on it once, on first use.
        // The device was created with vplkit::stages::required_device_features() (plain_vulkan.cpp):
        // Vulkan 1.3, VK_KHR_push_descriptor, shaderInt64, scalarBlockLayout, synchronization2,
        // dynamicRendering.
        vplkit::stages::Device kit(gpu.physical_device, gpu.device);

        // Buffers, sized by the stages' requirements and allocated by the "renderer".
        const uint32_t n = kVplCount;
        const uint32_t leaves = vplkit::stages::leaf_count(n);
        const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        auto buffer = [&](VkDeviceSize bytes) { return dropin::HostBuffer::create(gpu, bytes, storage); };
        dropin::HostBuffer vpls = buffer(n * sizeof(vplkit::shaders::Vpl));
        dropin::HostBuffer bounds = buffer(vplkit::stages::kVplBoundsBytes);
        dropin::HostBuffer keys = buffer(n * sizeof(uint64_t));
        dropin::HostBuffer values = buffer(n * sizeof(uint32_t));
        const auto sort_needs = vplkit::stages::radix_sort_requirements(kit.limits(), n);
        dropin::HostBuffer sort_keys = buffer(sort_needs.key_bytes);
        dropin::HostBuffer sort_values = buffer(sort_needs.value_bytes);
        dropin::HostBuffer sort_counts = buffer(sort_needs.count_bytes);
        dropin::HostBuffer leaf_buffer = buffer(leaves * sizeof(vplkit::shaders::Vpl));
        dropin::HostBuffer sst_nodes = buffer(vplkit::stages::sst_node_count(n) * sizeof(vplkit::shaders::SstNode));
        dropin::HostBuffer sst_counters = buffer(vplkit::stages::sst_counter_count(n) * sizeof(uint32_t));
        dropin::HostBuffer bvh_nodes = buffer(bvh.nodes.size() * sizeof(vplkit::shaders::BvhNode));
        dropin::HostBuffer bvh_triangles = buffer(bvh.triangles.size() * sizeof(vplkit::shaders::BvhTriangle));
        // The alpha-test records: one zero word, every triangle here is opaque.
        dropin::HostBuffer bvh_alpha = buffer(sizeof(uint32_t));
        dropin::HostBuffer counters = buffer(vplkit::stages::kGiCountersBytes);
        vplkit::stages::HybridOptions hybrid;  // the defaults (distances relative to the BVH's scene scale)...
        hybrid.samples_per_pixel = 16;         // ...but 16 samples per pixel
        const auto cut_needs = vplkit::stages::hybrid_cut_requirements(kSize, kSize, hybrid);
        dropin::HostBuffer cut_blocks = buffer(cut_needs.blocks_bytes);
        dropin::HostBuffer cut_nodes = buffer(cut_needs.cuts_bytes);
        std::memcpy(vpls.mapped, scene.vpls.data(), vpls.size);
        std::memcpy(bvh_nodes.mapped, bvh.nodes.data(), bvh_nodes.size);
        std::memcpy(bvh_triangles.mapped, bvh.triangles.data(), bvh_triangles.size);
        std::memset(bvh_alpha.mapped, 0, bvh_alpha.size);

        // The G-buffer and the output, uploaded through host buffers (RGBA32F and RGBA16F).
        using vplkit::stages::kGbufferAlbedoFormat;
        using vplkit::stages::kGbufferPositionFormat;
        auto image = [&](VkFormat format) { return dropin::StorageImage::create(gpu, kSize, kSize, format); };
        dropin::StorageImage position = image(kGbufferPositionFormat), normal = image(kGbufferPositionFormat),
                             geometric_normal = image(kGbufferPositionFormat), albedo = image(kGbufferAlbedoFormat),
                             indirect = image(VK_FORMAT_R32G32B32A32_SFLOAT);
        std::vector<dropin::HostBuffer> uploads;
        auto upload = [&](const void* texels, VkDeviceSize bytes) {
            uploads.push_back(dropin::HostBuffer::create(gpu, bytes, 0));
            std::memcpy(uploads.back().mapped, texels, bytes);
            return uploads.back();
        };
        const VkDeviceSize rgba32 = kSize * kSize * 16;
        const dropin::HostBuffer texels[] = {upload(scene.position.data(), rgba32), upload(scene.normal.data(), rgba32),
                                             upload(scene.geometric_normal.data(), rgba32),
                                             upload(scene.albedo.data(), rgba32 / 2)};
        dropin::HostBuffer readback = dropin::HostBuffer::create(gpu, rgba32, 0);

        // The kit's stages, appended to a StepList over the renderer's handles...
        vplkit::StepList steps;
        vplkit::stages::add_vpl_key_passes(
            kit, steps, {view(vpls, "vpls"), view(bounds, "bounds"), view(keys, "keys"), view(values, "values")}, n);
        vplkit::stages::RadixSorter sorter(
            kit, n, {view(sort_keys, "sort keys"), view(sort_values, "sort values"), view(sort_counts, "sort counts")});
        sorter.add_pass(steps, view(keys, "keys"), view(values, "values"), n);
        vplkit::stages::add_gather_leaves_pass(kit, steps, view(vpls, "vpls"), view(values, "values"),
                                               view(leaf_buffer, "leaves"), n);
        vplkit::stages::SstOptions sst;  // sigma_max is a length: scaled to the scene as the runtime does
        sst.sigma_max = 0.012f * bvh.scene_scale;
        vplkit::stages::add_sst_passes(kit, steps, view(leaf_buffer, "leaves"), view(sst_nodes, "sst"),
                                       view(sst_counters, "sst counters"), n, sst);
        vplkit::stages::GbufferViews gbuffer;
        gbuffer.position = view(position, "position");
        gbuffer.normal = view(normal, "normal");
        gbuffer.geometric_normal = view(geometric_normal, "geometric normal");
        gbuffer.albedo = view(albedo, "albedo");
        const vplkit::stages::BvhBuffers bvh_views{view(bvh_nodes, "bvh nodes"),
                                                   view(bvh_triangles, "bvh triangles"),
                                                   uint32_t(bvh.nodes.size()),
                                                   uint32_t(bvh.triangles.size()),
                                                   bvh.scene_scale,
                                                   view(bvh_alpha, "bvh alpha"),
                                                   /*alpha_tests=*/false};
        // hybrid reads only the leaves and the SST; the light tree view is rtslc's (any buffer will do).
        const vplkit::stages::VplTreeBuffers trees{n, leaves, view(leaf_buffer, "leaves"), view(sst_nodes, "sst"),
                                                   view(sst_nodes, "sst")};
        const vplkit::stages::HybridCutBuffers cuts{cut_needs.blocks_x, cut_needs.blocks_y, cut_needs.cut_size,
                                                    view(cut_blocks, "cut blocks"), view(cut_nodes, "cuts")};
        vplkit::stages::add_hybrid_gi_passes(kit, steps, gbuffer, bvh_views, trees, glm::vec3(0.0f, 3.0f, 0.0f),
                                             view(indirect, "indirect"), view(counters, "gi counters"), cuts, hybrid);

        // ...and recorded into the renderer's command buffer, between the renderer's own commands.
        gpu.submit([&](VkCommandBuffer cmd) {
            for (const dropin::StorageImage* i : {&position, &normal, &geometric_normal, &albedo, &indirect}) {
                dropin::to_general(cmd, *i);
            }
            copy_buffer_to_image(cmd, texels[0], position);
            copy_buffer_to_image(cmd, texels[1], normal);
            copy_buffer_to_image(cmd, texels[2], geometric_normal);
            copy_buffer_to_image(cmd, texels[3], albedo);
            steps.record(cmd);  // barriers between the stages' own steps are the kit's
            copy_image_to_buffer(cmd, indirect, readback);
        });

        // The check, and the picture.
        const float* rgba = static_cast<const float*>(readback.mapped);
        glm::dvec3 mean(0.0);
        std::vector<uint8_t> png(kSize * kSize * 3);
        const glm::dvec3 expected = reference_mean(scene, bvh.scene_scale);
        for (uint32_t i = 0; i < kSize * kSize; ++i) {
            for (int c = 0; c < 3; ++c) {
                mean[c] += rgba[4 * i + c] / double(kSize * kSize);
                const double shown = rgba[4 * i + c] / (4.0 * expected[c]);  // the mean at a quarter of white
                png[3 * i + c] = uint8_t(255.0 * std::pow(std::clamp(shown, 0.0, 1.0), 1.0 / 2.2));
            }
        }
        stbi_write_png("dropin.png", kSize, kSize, 3, png.data(), kSize * 3);
        double worst = 0.0;
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(mean[c] / expected[c] - 1.0));
        const bool ok = worst <= 0.05;
        std::printf(
            "dropin: %s, %u VPLs, %ux%u hybrid GI at %u spp: mean indirect (%.5f, %.5f, %.5f), CPU sum "
            "(%.5f, %.5f, %.5f), worst channel %.1f%% (tolerance 5%%), dropin.png written: %s\n",
            gpu.name.c_str(), n, kSize, kSize, hybrid.samples_per_pixel, mean.x, mean.y, mean.z, expected.x, expected.y,
            expected.z, 100.0 * worst, ok ? "ok" : "FAILED");

        for (dropin::HostBuffer* b :
             {&vpls, &bounds, &keys, &values, &sort_keys, &sort_values, &sort_counts, &leaf_buffer, &sst_nodes,
              &sst_counters, &bvh_nodes, &bvh_triangles, &bvh_alpha, &counters, &cut_blocks, &cut_nodes, &readback}) {
            b->destroy(gpu);
        }
        for (dropin::HostBuffer& b : uploads) b.destroy(gpu);
        for (dropin::StorageImage* i : {&position, &normal, &geometric_normal, &albedo, &indirect}) i->destroy(gpu);
        kit.destroy_pipelines();
        gpu.destroy();
        return ok ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "dropin: error: %s\n", e.what());
        return 1;
    }
}

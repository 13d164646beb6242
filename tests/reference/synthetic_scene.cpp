#include "synthetic_scene.hpp"

#include "vplkit/bvh.hpp"
#include "vplkit/shaders/types.hpp"

#include <glm/gtc/packing.hpp>

#include <array>

namespace vplkit::test {

namespace {

using Texel = std::array<float, 4>;
using HalfTexel = std::array<uint16_t, 4>;

HalfTexel to_half(float r, float g, float b, float a) {
    return {glm::packHalf1x16(r), glm::packHalf1x16(g), glm::packHalf1x16(b), glm::packHalf1x16(a)};
}

}  // namespace

float half_round(float v) {
    return glm::unpackHalf1x16(glm::packHalf1x16(v));
}

reference::Vec3 d3(glm::vec3 v) {
    return {v.x, v.y, v.z};
}

GpuSyntheticScene upload(Context& context, uint32_t width, uint32_t height, std::span<const Pixel> pixels,
                         std::span<const glm::vec3> triangles, std::span<const TestVpl> vpls) {
    GpuSyntheticScene out;
    // The layout of shaders/include/vplkit/gbuffer.glsl: coverage in position.w, roughness in
    // normal.w, metallic in geometric_normal.w.
    out.gbuffer = vplkit::GbufferImages::create(context, width, height);
    std::vector<Texel> position, normal, geometric;
    std::vector<HalfTexel> albedo, emission;
    for (const Pixel& p : pixels) {
        position.push_back({p.position.x, p.position.y, p.position.z, p.covered ? 1.0f : 0.0f});
        normal.push_back({p.normal.x, p.normal.y, p.normal.z, p.roughness});
        geometric.push_back({p.geometric.x, p.geometric.y, p.geometric.z, p.metallic});
        albedo.push_back(to_half(p.albedo.x, p.albedo.y, p.albedo.z, 1.0f));
        emission.push_back(to_half(0, 0, 0, 0));
    }
    out.gbuffer.position.upload(position);
    out.gbuffer.normal.upload(normal);
    out.gbuffer.geometric_normal.upload(geometric);
    out.gbuffer.albedo.upload(albedo);
    out.gbuffer.emission.upload(emission);
    out.bvh = upload_bvh(context, build_bvh(triangles));
    std::vector<shaders::Vpl> gpu_vpls;
    for (const TestVpl& v : vpls) {
        shaders::Vpl g{};
        g.position = {v.position.x, v.position.y, v.position.z};
        g.normal = {v.normal.x, v.normal.y, v.normal.z};
        g.flux = {v.flux.x, v.flux.y, v.flux.z};
        gpu_vpls.push_back(g);
    }
    if (gpu_vpls.empty()) gpu_vpls.push_back({});
    out.vpls = Buffer::create(context, gpu_vpls.size() * sizeof(shaders::Vpl), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              MemoryUse::device, "vpls");
    out.vpls.upload(gpu_vpls);
    return out;
}

reference::ShadingPoint shading_point(const Pixel& p) {
    return {d3(p.position), d3(p.normal), d3(p.geometric), d3(p.albedo), p.roughness, p.metallic};
}

std::vector<reference::VplDesc> reference_vpls(std::span<const TestVpl> vpls) {
    std::vector<reference::VplDesc> out;
    for (const TestVpl& v : vpls) out.push_back({d3(v.position), d3(v.normal), d3(v.flux)});
    return out;
}

std::vector<reference::Triangle> reference_triangles(std::span<const glm::vec3> triangles) {
    std::vector<reference::Triangle> out;
    for (size_t i = 0; i + 2 < triangles.size(); i += 3) {
        out.push_back({d3(triangles[i]), d3(triangles[i + 1]), d3(triangles[i + 2])});
    }
    return out;
}

}  // namespace vplkit::test

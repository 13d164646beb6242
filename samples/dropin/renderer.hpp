#pragma once
// The sample's renderer, as an engine that never heard of vplkit has it: a scene of coloured
// triangles, a point light in its own units, a camera, and one raster pass into colour (its
// direct light, RGBA16F), an octahedral normal (RG16F), albedo (RGBA8) and depth (D32, standard
// Z). Its shaders are its own (shaders/scene.vert, scene.frag); nothing here includes vplkit.

#include "plain_vulkan.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace dropin {

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec3 albedo;  // linear diffuse colour
};

struct Scene {
    std::vector<Vertex> vertices;  // 3 per triangle, world space
    glm::vec3 light_position{0.0f};
    // The renderer's light: a surface of albedo a at distance d, angle theta, gets
    // a * cos(theta) * light_color / d^2 (no 1 / pi).
    glm::vec3 light_color{0.0f};
};

// A floor, a back wall and a box standing on the floor, lit by a point light.
Scene make_scene();

struct Camera {
    glm::vec3 eye{0.0f};
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};       // Vulkan clip space: y down the image, depth 0 (near) .. 1 (far)
    glm::mat4 view_projection{1.0f};  // projection * view
};
Camera make_camera(uint32_t width, uint32_t height);

// The raster pass and its targets. draw() leaves colour in GENERAL and normal, albedo and depth
// in SHADER_READ_ONLY_OPTIMAL, for post passes to read, and `output` (the image the renderer
// shows: RGBA16F, storage) in GENERAL, for them to write.
struct Rasterizer {
    GpuImage colour, normal, albedo, depth, output;
    HostBuffer vertex_buffer;
    uint32_t vertex_count = 0;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;

    static Rasterizer create(const Gpu& gpu, const Scene& scene, uint32_t width, uint32_t height);
    void draw(VkCommandBuffer cmd, const Scene& scene, const Camera& camera) const;
    void destroy(const Gpu& gpu);
};

}  // namespace dropin

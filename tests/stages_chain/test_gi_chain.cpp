// The GI chain's requirements (stages/gi_chain.hpp) against what its stages check and use.
// Each case allocates exactly what gi_chain_requirements lists (no byte more), builds the chain
// through the allocation callbacks and records two frames over a small scene (a floor and a
// back wall lit by a point light; the camera sees the floor through a depth, normal and albedo
// the adapter reads): no stage throws for a too-small buffer, no validation message
// (synchronization validation included), for hybrid and rtslc (also interleaved, which needs
// one more image), with and without SVGF, and with images handed over as created (UNDEFINED, no
// layout pointer: the chain tracks their layouts). Then: every listed slot is used by some step (none the
// method does not read or write), each slot's usage flags cover how the steps use it, and the
// indirect light on the floor (from the VPLs on the wall) is finite and positive.

#include "vplkit_test/context.hpp"

#include "vplkit/bvh_gpu.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/render_settings.hpp"
#include "vplkit/stages/gi_chain.hpp"
#include "vplkit/stages/renderer_vpl_sources.hpp"

#include <doctest/doctest.h>
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>
#include <glm/matrix.hpp>

#include <cmath>
#include <deque>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace vs = vplkit::stages;

namespace {

constexpr uint32_t kSize = 32;

// The floor y = 0 and the back wall z = -1, both [-1, 1] wide, as a renderer hands them over,
// and what its raster pass would have left: depth (R32F copy), world normal (xyz), albedo.
struct Scene {
    vplkit::GpuBvh bvh;
    vplkit::Buffer source_block;
    vs::VplSourceBuffers sources;
    vplkit::Image depth, normal, albedo;
    glm::vec3 eye{0.0f, 1.2f, 2.0f};
    glm::mat4 view_projection{1.0f};
};

Scene make_scene(vplkit::Context& context) {
    Scene s;
    const std::vector<glm::vec3> triangles = {{-1, 0, 1}, {1, 0, 1},   {1, 0, -1},  {-1, 0, 1},
                                              {1, 0, -1}, {-1, 0, -1}, {-1, 0, -1}, {1, 0, -1},
                                              {1, 2, -1}, {-1, 0, -1}, {1, 2, -1},  {-1, 2, -1}};
    s.bvh = vplkit::upload_bvh(context, vplkit::build_bvh(triangles));
    vs::RendererLight light;
    light.position = {0.0f, 1.0f, 0.0f};
    light.intensity = glm::vec3(2.0f);
    const vs::VplSourceData data = vs::vpl_sources_from_renderer({&light, 1}, {}, {triangles, {}, glm::vec3(0.6f)});
    s.source_block = vplkit::Buffer::create(context, data.bytes(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                            vplkit::MemoryUse::upload, "vpl sources");
    std::vector<uint8_t> bytes(data.bytes());
    data.write(bytes.data());
    s.source_block.upload(bytes.data(), bytes.size());
    s.sources = data.views(s.source_block);

    glm::mat4 projection = glm::perspectiveRH_ZO(glm::radians(60.0f), 1.0f, 0.1f, 10.0f);
    projection[1][1] = -projection[1][1];  // Vulkan's clip y points down the image
    s.view_projection = projection * glm::lookAtRH(s.eye, glm::vec3(0.0f, 0.0f, -0.3f), glm::vec3(0, 1, 0));
    // Each pixel's ray against the floor: its depth where it hits inside [-1, 1]^2, else far.
    const glm::mat4 inverse = glm::inverse(s.view_projection);
    std::vector<float> depth(kSize * kSize, 1.0f);
    for (uint32_t y = 0; y < kSize; ++y) {
        for (uint32_t x = 0; x < kSize; ++x) {
            const glm::vec2 clip((x + 0.5f) / kSize * 2.0f - 1.0f, (y + 0.5f) / kSize * 2.0f - 1.0f);
            const glm::vec4 far = inverse * glm::vec4(clip, 1.0f, 1.0f);
            const glm::vec3 direction = glm::vec3(far) / far.w - s.eye;
            const float t = -s.eye.y / direction.y;
            const glm::vec3 hit = s.eye + t * direction;
            if (t <= 0.0f || std::abs(hit.x) > 1.0f || std::abs(hit.z) > 1.0f) continue;
            const glm::vec4 projected = s.view_projection * glm::vec4(hit, 1.0f);
            depth[y * kSize + x] = projected.z / projected.w;
        }
    }
    const VkImageUsageFlags sampled = VK_IMAGE_USAGE_SAMPLED_BIT;
    s.depth = vplkit::Image::create(context, kSize, kSize, VK_FORMAT_R32_SFLOAT, sampled, "depth");
    s.depth.upload(depth);
    s.normal = vplkit::Image::create(context, kSize, kSize, VK_FORMAT_R16G16B16A16_SFLOAT, sampled, "normal");
    const uint16_t one = glm::packHalf1x16(1.0f);
    std::vector<uint16_t> normals(kSize * kSize * 4, 0);
    for (size_t i = 0; i < kSize * kSize; ++i) normals[4 * i + 1] = one;  // up
    s.normal.upload(normals);
    s.albedo = vplkit::Image::create(context, kSize, kSize, VK_FORMAT_R8G8B8A8_UNORM, sampled, "albedo");
    s.albedo.upload(std::vector<uint8_t>(kSize * kSize * 4, 153));
    return s;
}

// The caller's side: exactly the listed bytes, formats and sizes, kept by slot name.
struct Allocations {
    std::deque<vplkit::Buffer> buffers;
    std::deque<vplkit::Image> images;
    std::map<VkBuffer, vs::BufferRequirement> buffer_needs;
    std::map<VkImage, vs::ImageRequirement> image_needs;
    std::string shortened;   // a slot allocated 4 bytes short, for the refusal test
    bool untracked = false;  // images returned without a layout pointer, as created (UNDEFINED)

    vs::GiChain chain(vplkit::Context& context, const vs::GiChainOptions& options) {
        return vs::GiChain(
            context, options,
            [this, &context](const vs::BufferRequirement& need) {
                const VkDeviceSize bytes = need.name == shortened ? need.bytes - 4 : need.bytes;
                buffers.push_back(vplkit::Buffer::create(context, bytes, need.usage, vplkit::MemoryUse::device));
                buffer_needs[buffers.back().handle()] = need;
                return vplkit::BufferView(buffers.back());  // unnamed: the chain names it by its slot
            },
            [this, &context](const vs::ImageRequirement& need) {
                images.push_back(
                    vplkit::Image::create(context, need.width, need.height, need.format, need.usage, need.name));
                image_needs[images.back().handle()] = need;
                if (untracked) return vplkit::ImageView(std::as_const(images.back()));  // the chain tracks it
                return vplkit::ImageView(images.back());                                // with its tracked layout
            });
    }
};

vs::GiChainOptions options_for(vs::GiChainMethod method, bool denoise, uint32_t interleave = 1) {
    vs::GiChainOptions o;
    o.method = method;
    o.width = o.height = kSize;
    o.tracing = {256, 2, 3};
    o.denoise = denoise;
    o.hybrid.samples_per_pixel = 4;
    o.rtslc.samples_per_pixel = 4;
    o.rtslc.interleave = interleave;
    o.rtslc.block_size = 4;
    return o;
}

}  // namespace

TEST_CASE("gi chain: what gi_chain_requirements lists is what the stages check and use") {
    vplkit::Context& context = vplkit::test::context();
    Scene scene = make_scene(context);
    struct Case {
        const char* name;
        vs::GiChainMethod method;
        bool denoise;
        uint32_t interleave;
        bool untracked = false;
    };
    for (const Case& c :
         {Case{"hybrid", vs::GiChainMethod::hybrid, false, 1},
          Case{"hybrid + svgf", vs::GiChainMethod::hybrid, true, 1}, Case{"rtslc", vs::GiChainMethod::rtslc, false, 1},
          Case{"rtslc + svgf", vs::GiChainMethod::rtslc, true, 1},
          Case{"rtslc interleaved", vs::GiChainMethod::rtslc, false, 2},
          Case{"hybrid + svgf, images as created", vs::GiChainMethod::hybrid, true, 1, true}}) {
        CAPTURE(std::string(c.name));
        Allocations memory;
        memory.untracked = c.untracked;
        vs::GiChain chain = memory.chain(context, options_for(c.method, c.denoise, c.interleave));
        const vs::GiChainRequirements& needs = chain.requirements();
        CHECK(needs.vpl_capacity == 512);
        // Each method lists its own tree only, and SVGF's images only with the denoiser.
        auto lists = [&](const std::string& name) {
            for (const vs::BufferRequirement& b : needs.buffers) {
                if (b.name == name) return true;
            }
            for (const vs::ImageRequirement& i : needs.images) {
                if (i.name == name) return true;
            }
            return false;
        };
        CHECK(lists("sst") == (c.method == vs::GiChainMethod::hybrid));
        CHECK(lists("light tree") == (c.method == vs::GiChainMethod::rtslc));
        CHECK(lists("svgf 0") == c.denoise);
        CHECK(lists("rtslc estimates") == (c.interleave > 1));

        for (uint32_t frame = 0; frame < 2; ++frame) {
            vplkit::PassList steps;
            const vs::GiChainFrame f{frame, scene.eye, scene.view_projection};
            chain.add_gi_passes(steps, {scene.bvh, scene.sources, {scene.depth, scene.normal, scene.albedo, {}}}, f);
            if (c.denoise) chain.add_denoise_passes(steps, f);
            steps.run(context);

            // Every slot the chain asked for is used, under the slot's name, by some step.
            std::map<VkBuffer, std::string> used_buffers;
            std::map<VkImage, std::string> used_images;
            for (const vplkit::ResourceUse& u : steps.entry()) {
                if (u.buffer) used_buffers[u.buffer] = u.name;
                if (u.image) used_images[u.image] = u.name;
            }
            for (const auto& [handle, need] : memory.buffer_needs) {
                CAPTURE(need.name);
                CHECK(used_buffers.count(handle) == 1);
                CHECK(used_buffers[handle] == need.name);
            }
            for (const auto& [handle, need] : memory.image_needs) {
                CAPTURE(need.name);
                CHECK(used_images.count(handle) == 1);
            }
            // The usage flags cover the steps' uses (the runtime's Buffer and Image add transfer
            // usage on their own, so validation alone would not tell).
            for (const vplkit::Step& step : steps.steps()) {
                for (const vplkit::Use& use : step.uses) {
                    if (use.is_image()) {
                        if (!memory.image_needs.count(use.image.image)) continue;  // the renderer's
                        const vs::ImageRequirement& need = memory.image_needs[use.image.image];
                        CAPTURE(need.name);
                        CHECK((need.usage & VK_IMAGE_USAGE_STORAGE_BIT) != 0);
                        continue;
                    }
                    if (!memory.buffer_needs.count(use.buffer.buffer)) continue;  // the scene's
                    const vs::BufferRequirement& need = memory.buffer_needs[use.buffer.buffer];
                    CAPTURE(need.name);
                    CAPTURE(step.name);
                    if (has_stage(use.stages, vplkit::Stage::compute)) {
                        CHECK((need.usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) != 0);
                    }
                    if (has_stage(use.stages, vplkit::Stage::transfer) && use.access != vplkit::Access::read) {
                        CHECK((need.usage & VK_BUFFER_USAGE_TRANSFER_DST_BIT) != 0);
                    }
                }
            }
        }

        // The floor sees the VPLs on the wall: finite, positive light.
        vplkit::Image* indirect = nullptr;
        for (vplkit::Image& i : memory.images) {
            if (i.handle() == chain.indirect().image) indirect = &i;
        }
        REQUIRE(indirect != nullptr);
        const std::vector<float> texels = indirect->download<float>();
        double sum = 0.0;
        bool finite = true;
        for (size_t i = 0; i < texels.size(); i += 4) {
            for (int k = 0; k < 3; ++k) finite = finite && std::isfinite(texels[i + k]) && texels[i + k] >= 0.0f;
            sum += texels[i];
        }
        CHECK(finite);
        CHECK(sum > 0.0);
    }
}

TEST_CASE("gi chain: a view smaller than its requirement is refused, naming the slot") {
    vplkit::Context& context = vplkit::test::context();
    Allocations memory;
    memory.shortened = "sst counters";
    CHECK_THROWS_WITH_AS(memory.chain(context, options_for(vs::GiChainMethod::hybrid, true)),
                         doctest::Contains("'sst counters'"), vplkit::Error);
}

TEST_CASE("gi chain: sigma_max's default share of the scene scale is the runtime's") {
    CHECK(vs::kGiChainSigmaMaxSceneFraction == vplkit::kSigmaMaxSceneFraction);
    CHECK(vs::GiChainOptions{}.sigma_max_scene_fraction.value() == vplkit::kSigmaMaxSceneFraction);
}

TEST_CASE(
    "gi chain: GiChainFrame::from_camera takes the eye, view-projection and view_to_world from view and projection") {
    const glm::vec3 eye{1.2f, 1.8f, 3.2f};
    const glm::mat4 view = glm::lookAtRH(eye, glm::vec3(0.0f, 0.4f, -0.5f), glm::vec3(0, 1, 0));
    glm::mat4 projection = glm::perspectiveRH_ZO(glm::radians(55.0f), 16.0f / 9.0f, 50.0f, 0.1f);  // reversed Z
    projection[1][1] = -projection[1][1];
    const vs::GiChainFrame frame = vs::GiChainFrame::from_camera(7, view, projection);
    CHECK(frame.index == 7);
    for (int i = 0; i < 3; ++i) CHECK(frame.camera_position[i] == doctest::Approx(eye[i]).epsilon(1e-5));
    CHECK(frame.view_projection == projection * view);
    // A world direction taken to view space by the view comes back.
    const glm::vec3 world_normal = glm::normalize(glm::vec3(0.3f, 0.8f, -0.5f));
    const glm::vec3 back = frame.view_to_world * glm::vec3(view * glm::vec4(world_normal, 0.0f));
    for (int i = 0; i < 3; ++i) CHECK(back[i] == doctest::Approx(world_normal[i]).epsilon(1e-5));
    CHECK(glm::length(glm::vec3(frame.view_to_world[2]) - glm::normalize(eye - glm::vec3(0.0f, 0.4f, -0.5f))) <
          1e-5f);  // the camera's +z axis, world space: away from the target
}

#pragma once
// The GI chain in one object, for a renderer that takes the kit from outside: every buffer and
// image it needs listed by one query, allocated through the caller's callbacks, and the stages
// recorded in order into the caller's StepList each frame:
//
//   VPLs traced from the scene (count kept on the GPU) -> keys -> radix sort -> leaves
//   -> the method's tree (hybrid: SST; rtslc: light tree) -> the kit's G-buffer from the
//   renderer's depth, normal and albedo (gbuffer_adapter.hpp) -> indirect light -> SVGF (optional)
//
//   vplkit::stages::GiChainOptions o;            // method, size, paths, adapter encoding...
//   vplkit::stages::GiChain gi(device, o, allocate_buffer, allocate_image);
//   vplkit::StepList steps;
//   gi.add_gi_passes(steps, {bvh, sources, {depth, normal, albedo, {}}}, frame);
//   gi.add_denoise_passes(steps, frame);          // options.denoise only
//   vplkit::stages::add_compose_pass(device, steps, colour, gi.indirect(), output);
//   // barriers from steps.entry(), steps.record(cmd), barriers from steps.exit()
//
// Why callbacks rather than a struct the caller fills: the caller writes one allocation function
// per kind (buffer, image) whatever the method, never learns the chain's slots by name, and the
// kit checks each view against its requirement the moment it comes back (a wrong size is an
// error naming the slot, not a stage's throw frames later). gi_chain_requirements() is the same
// list for callers that plan memory up front (aliasing, a frame graph): their callback then
// looks the slot up by name. Lists only what the chosen method and options read or write.
//
// Lengths: none to set. sst.sigma_max is sigma_max_scene_fraction of the BVH's scene scale (as
// the runtime's Renderer does), SVGF's lengths are shares of the same scale, and hybrid's and
// rtslc's similarity distance are scene-relative when 0 (their default).

#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit/stages/denoise.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/stages/gbuffer_adapter.hpp"
#include "vplkit/stages/gbuffer_views.hpp"
#include "vplkit/stages/hybrid_gi.hpp"
#include "vplkit/stages/light_tree.hpp"
#include "vplkit/stages/radix_sort.hpp"
#include "vplkit/stages/rtslc.hpp"
#include "vplkit/stages/sst.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"
#include "vplkit/stages/vpl_keys.hpp"
#include "vplkit/stages/vpl_tracing.hpp"
#include "vplkit/stages/vpl_tree_buffers.hpp"

#include <vulkan/vulkan.h>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace vplkit::stages {

// sst.sigma_max as a share of the scene scale: the runtime's default (kSigmaMaxSceneFraction,
// render_settings.hpp, which says how it was measured), the same value.
inline constexpr float kGiChainSigmaMaxSceneFraction = 0.012f;

enum class GiChainMethod { hybrid, rtslc };

struct GiChainOptions {
    GiChainMethod method = GiChainMethod::hybrid;
    uint32_t width = 0, height = 0;  // the renderer's G-buffer and output size
    // Light paths and bounces per frame (their product is the VPL capacity); the seed is added
    // to GiChainFrame::index, so every frame traces other VPLs.
    VplTracingOptions tracing{1024, 2, 0};
    // How the renderer's depth, normal and albedo are stored (inverse_view_projection and
    // view_to_world are taken from GiChainFrame each frame).
    GbufferAdapterOptions adapter;
    bool denoise = true;  // SVGF (svgf.hpp) after the GI; its images are listed only when set
    HybridOptions hybrid;
    RtslcOptions rtslc;
    SstOptions sst;  // hybrid; sigma_max is replaced as below unless the fraction is unset
    std::optional<float> sigma_max_scene_fraction = kGiChainSigmaMaxSceneFraction;
    LightTreeOptions light_tree;     // rtslc
    DenoiseOptions denoise_options;  // scene_scale is the BVH's, set each frame
    RadixSortOptions sort;
};

// One buffer the chain reads or writes: `bytes` at least, with `usage`.
struct BufferRequirement {
    std::string name;  // the slot; the chain names the caller's view so when the view has no name
    VkDeviceSize bytes = 0;
    VkBufferUsageFlags usage = 0;
};

// One image: this format and size exactly, with `usage`, in any layout (as created: UNDEFINED).
// The chain keeps the layout of a view returned without a layout pointer itself, from UNDEFINED
// (its first recording moves it; what it held is not kept); a view with one is moved from there.
// Layouts move as a StepList is recorded: record the lists in the order the chain filled them.
struct ImageRequirement {
    std::string name;
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t width = 0, height = 0;
    VkImageUsageFlags usage = 0;
};

struct GiChainRequirements {
    uint32_t vpl_capacity = 0;  // the most VPLs a frame traces (the trees are sized for it)
    std::vector<BufferRequirement> buffers;
    std::vector<ImageRequirement> images;
};

// Everything the chain reads or writes besides its inputs (GiChainInputs: the scene's BVH and
// VPL sources, the renderer's images), for these options on a device with these limits. Throws
// vplkit::Error naming a bad option (a zero size, bad tracing, sampler or sort options).
GiChainRequirements gi_chain_requirements(const Limits& limits, const GiChainOptions& options);

// What the caller hands the chain each frame.
struct GiChainInputs {
    BvhBuffers bvh;                // the scene's (its scene_scale sets every length)
    VplSourceBuffers sources;      // what the VPLs are traced from (renderer_vpl_sources.hpp)
    GbufferAdapterInputs gbuffer;  // the renderer's depth, normal, albedo (and material) images
};

struct GiChainFrame {
    // Seeds the VPLs and the samplers; 0 also starts SVGF's history over (the first frame, a cut).
    uint32_t index = 0;
    glm::vec3 camera_position{0.0f};
    glm::mat4 view_projection{1.0f};  // world -> Vulkan clip, what the depth was rendered with
    // Only for view-space normals (GbufferNormalSpace::view). Its default, identity, reads them as
    // world-space normals without a word: from_camera sets it.
    glm::mat3 view_to_world{1.0f};

    // Every member from the camera the raster pass used: `view` world -> view (a rigid
    // transform, as lookAt's), `projection` view -> Vulkan clip (reversed Z or not, y down).
    static GiChainFrame from_camera(uint32_t index, const glm::mat4& view, const glm::mat4& projection) {
        const glm::mat4 camera_to_world = glm::inverse(view);
        return {index, glm::vec3(camera_to_world[3]), projection * view, glm::mat3(camera_to_world)};
    }
};

class GiChain {
public:
    using AllocateBuffer = std::function<BufferView(const BufferRequirement&)>;
    using AllocateImage = std::function<ImageView(const ImageRequirement&)>;

    // Calls the allocators once per requirement of gi_chain_requirements(device.limits(),
    // options) and keeps the views (the memory stays the caller's: free it after the chain's
    // last recording ran). Throws vplkit::Error for bad options or a view that does not meet its
    // requirement (too small, another format or size), naming the slot.
    GiChain(Device& device, const GiChainOptions& options, const AllocateBuffer& allocate_buffer,
            const AllocateImage& allocate_image);

    // VPLs -> trees -> G-buffer -> indirect(), for this frame. The chain (at this address) and
    // the inputs' buffers must outlive the recording of `steps`.
    void add_gi_passes(StepList& steps, const GiChainInputs& inputs, const GiChainFrame& frame);
    // SVGF on indirect(), in place (options.denoise; Error otherwise). After add_gi_passes of
    // the same frame.
    void add_denoise_passes(StepList& steps, const GiChainFrame& frame);

    const GiChainRequirements& requirements() const { return requirements_; }
    const ImageView& indirect() const { return indirect_; }      // RGBA32F: rgb the indirect light
    const GbufferViews& gbuffer() const { return gbuffer_; }     // the kit's, from the adapter
    const VplTracingBuffers& vpls() const { return tracing_; }   // this frame's VPLs and their count
    const BufferView& counters() const { return gi_counters_; }  // GiCounters (gi_counters.hpp)

private:
    Device* device_;
    GiChainOptions options_;
    GiChainRequirements requirements_;
    VplTracingBuffers tracing_;
    VplKeyBuffers keys_;
    std::unique_ptr<RadixSorter> sorter_;
    VplTreeBuffers trees_;
    BufferView sst_counters_, gi_counters_;
    HybridCutBuffers hybrid_cuts_;
    RtslcScratchBuffers rtslc_scratch_;
    GbufferViews gbuffer_;
    ImageView indirect_;
    std::vector<ImageView> svgf_;
    std::deque<VkImageLayout> image_layouts_;   // of the caller's images returned without a layout pointer
    float scene_scale_ = 1.0f;                  // the last add_gi_passes' BVH's
    glm::mat4 previous_view_projection_{1.0f};  // unused by SVGF's first frame (index 0)
};

}  // namespace vplkit::stages

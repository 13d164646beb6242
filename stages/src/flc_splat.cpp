#include "vplkit/error.hpp"
#include "vplkit/graphics_pipeline.hpp"
#include "vplkit/shaders/flc_splat_shade.hpp"
#include "vplkit/shaders/flc_splat_args.hpp"
#include "vplkit/shaders/flc_splat_proxy.hpp"
#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/flc.hpp"

#include <cmath>
#include <cstring>
#include <string>

namespace vplkit::stages {
namespace {

namespace vert = shaders::flc_splat_proxy;
namespace frag = shaders::flc_splat_shade;

struct FlcSplatPipelineDescription {
    static RasterState state() {
        RasterState s;
        s.color_formats = {kFlcIndirectFormat};
        s.cull_mode = VK_CULL_MODE_NONE;  // the rectangles' winding is not a side
        s.depth_test = false;
        s.depth_write = false;
        s.additive_blend = true;  // each VPL adds its share (seed 002 sec. 5)
        return s;
    }
};
using FlcSplatPipeline = RasterPipeline<vert::Module, frag::Module, FlcSplatPipelineDescription>;

}  // namespace

void add_flc_splat_passes(Device& device, StepList& passes, const FlcSplatBuffers& buffers, const GbufferViews& gbuffer,
                          const ImageView& indirect, const CameraView& view, const FlcPartition& partition,
                          uint32_t vpl_capacity, float scene_scale) {
    validate(partition);
    if (vpl_capacity == 0) throw Error("flc splat: the VPL buffer holds no VPL");
    if (!std::isfinite(scene_scale) || !(scene_scale > 0.0f)) {
        throw Error("flc splat: scene scale " + std::to_string(scene_scale) + " must be finite and positive");
    }
    const auto need = [](const BufferView& view, uint64_t bytes, const char* what) {
        if (view.size < bytes) {
            throw Error("flc splat: '" + std::string(what) + "' has " + std::to_string(view.size) + " bytes, " +
                        std::to_string(bytes) + " needed");
        }
    };
    need(buffers.kept_triangles, uint64_t(vpl_capacity) * sizeof(uint32_t), "kept triangles");
    need(buffers.vpls, uint64_t(vpl_capacity) * sizeof(shaders::Vpl), "vpls");
    need(buffers.counts, sizeof(uint32_t), "counts");
    need(buffers.draw_args, kFlcDrawArgsBytes, "draw args");
    if (indirect.width != gbuffer.width() || indirect.height != gbuffer.height()) {
        throw Error("flc splat: the indirect image is " + std::to_string(indirect.width) + "x" +
                    std::to_string(indirect.height) + ", the G-buffer " + std::to_string(gbuffer.width()) + "x" +
                    std::to_string(gbuffer.height()));
    }
    if (indirect.format != kFlcIndirectFormat) throw Error("flc splat: the indirect image must be RGBA32F");

    namespace args = shaders::flc_splat_args;
    const auto& args_pipeline = device.pipeline<args::Pipeline>();
    args::Bindings args_bindings;
    args_bindings.counts = buffers.counts.descriptor();
    args_bindings.draw = buffers.draw_args.descriptor();
    args::Push args_push{};
    args_push.vpl_capacity = vpl_capacity;
    passes.add("flc splat args", binding_uses<args::Module>(args_bindings),
               [&args_pipeline, args_bindings, args_push](VkCommandBuffer cmd) {
                   args_pipeline.dispatch(cmd, args_bindings, args_push, 1);
               });

    const GraphicsPipeline& pipeline = device.pipeline<FlcSplatPipeline>().pipeline;
    vert::Bindings vpl_bindings;
    vpl_bindings.candidates = buffers.candidates.descriptor();
    vpl_bindings.kept_triangles = buffers.kept_triangles.descriptor();
    vpl_bindings.vpls = buffers.vpls.descriptor();
    frag::Bindings gbuffer_bindings;
    gbuffer_bindings.gbuffer_position = gbuffer.position.descriptor();
    gbuffer_bindings.gbuffer_normal = gbuffer.normal.descriptor();
    gbuffer_bindings.gbuffer_geometric_normal = gbuffer.geometric_normal.descriptor();
    gbuffer_bindings.gbuffer_albedo = gbuffer.albedo.descriptor();
    frag::Push push{};
    std::memcpy(&push.view_projection, &view.view_projection, sizeof(push.view_projection));
    push.camera_position = {view.position.x, view.position.y, view.position.z};
    push.scene_scale = scene_scale;
    push.pixel_size = {2.0f / float(indirect.width), 2.0f / float(indirect.height)};
    push.level_count = partition.level_count;
    push.d0 = partition.d0;
    push.mu = partition.mu;
    std::vector<Use> uses = binding_uses<vert::Module>(vpl_bindings, {}, Stage::vertex);
    const std::vector<Use> reads = binding_uses<frag::Module>(
        gbuffer_bindings, {gbuffer.position, gbuffer.normal, gbuffer.geometric_normal, gbuffer.albedo},
        Stage::fragment);
    uses.insert(uses.end(), reads.begin(), reads.end());
    uses.push_back(Use::indirect(buffers.draw_args));
    uses.push_back(Use::color_attachment(indirect));
    const BufferView draw_args = buffers.draw_args;
    // Views by value: the caller's may be temporaries that are gone when the steps are recorded.
    passes.add("flc splat", uses,
               [&pipeline, vpl_bindings, gbuffer_bindings, push, indirect, draw_args](VkCommandBuffer cmd) {
                   begin_rendering(cmd, {{indirect}, {VkClearColorValue{{0.0f, 0.0f, 0.0f, 0.0f}}}, {}, 1.0f});
                   pipeline.bind(cmd);
                   pipeline.push_descriptors<vert::Module, frag::Module>(cmd, vpl_bindings, gbuffer_bindings);
                   pipeline.push_constants(cmd, push);
                   vkCmdDrawIndirect(cmd, draw_args.buffer, draw_args.offset, 1, sizeof(VkDrawIndirectCommand));
                   end_rendering(cmd);
               });
}

}  // namespace vplkit::stages

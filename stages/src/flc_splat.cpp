#include "vplkit/error.hpp"
#include "vplkit/graphics_pipeline.hpp"
#include "vplkit/shaders/flc_splat_shade.hpp"
#include "vplkit/shaders/flc_splat_args.hpp"
#include "vplkit/shaders/flc_splat_proxy.hpp"
#include "vplkit/shaders/flc_untile.hpp"
#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/flc.hpp"
#include "vplkit/stages/gi_similarity.hpp"

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
        s.additive_blend = true;  // each VPL adds its share (the FLC paper sec. 5)
        return s;
    }
};
using FlcSplatPipeline = RasterPipeline<vert::Module, frag::Module, FlcSplatPipelineDescription>;

}  // namespace

void add_flc_splat_passes(Device& device, StepList& passes, const FlcSplatBuffers& buffers, const GbufferViews& gbuffer,
                          const ImageView& indirect, const CameraView& view, const FlcPartition& partition,
                          uint32_t vpl_capacity, float scene_scale, const FlcSplatOptions& options,
                          const ImageView& tiled) {
    // Report the caller's names, not the bindings' (StepList::name).
    passes.names({buffers.candidates, buffers.counts, buffers.kept_triangles, buffers.vpls, buffers.draw_args});
    validate(partition);
    const uint32_t n = options.subtiles;
    if (n < 1 || n > kFlcMaxSubtiles) {
        throw Error("flc splat: " + std::to_string(n) + " sub-tiles per side, expected 1.." +
                    std::to_string(kFlcMaxSubtiles));
    }
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
    const uint32_t side_x = flc_subtile_side(indirect.width, n), side_y = flc_subtile_side(indirect.height, n);
    if (n > 1 &&
        (!tiled || tiled.width != n * side_x || tiled.height != n * side_y || tiled.format != kFlcIndirectFormat)) {
        throw Error("flc splat: " + std::to_string(n) + "x" + std::to_string(n) +
                    " sub-tiles need an RGBA32F tiled image of " + std::to_string(n * side_x) + "x" +
                    std::to_string(n * side_y));
    }
    const ImageView target = n > 1 ? tiled : indirect;

    namespace args = shaders::flc_splat_args;
    const auto& args_pipeline = device.pipeline<args::Pipeline>();
    args::Bindings args_bindings;
    args_bindings.counts = buffers.counts.descriptor();
    args_bindings.draw = buffers.draw_args.descriptor();
    args::Push args_push{};
    args_push.vpl_capacity = vpl_capacity;
    add_dispatch<args::Module>(passes, "flc splat args", args_pipeline, args_bindings, args_push, 1);

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
    push.image_size = {indirect.width, indirect.height};
    push.subtile_size = {side_x, side_y};
    push.subtiles = n;
    push.level_count = partition.level_count;
    push.d0 = partition.d0;
    push.mu = partition.mu;
    std::vector<Use> uses = binding_uses<vert::Module>(vpl_bindings, {}, Stage::vertex);
    const std::vector<Use> reads = binding_uses<frag::Module>(
        gbuffer_bindings, {gbuffer.position, gbuffer.normal, gbuffer.geometric_normal, gbuffer.albedo},
        Stage::fragment);
    uses.insert(uses.end(), reads.begin(), reads.end());
    uses.push_back(Use::indirect(buffers.draw_args));
    uses.push_back(Use::color_attachment(target));
    const BufferView draw_args = buffers.draw_args;
    // Views by value: the caller's may be temporaries that are gone when the steps are recorded.
    passes.add("flc splat", uses,
               [&pipeline, vpl_bindings, gbuffer_bindings, push, target, draw_args](VkCommandBuffer cmd) {
                   begin_rendering(cmd, {{target}, {VkClearColorValue{{0.0f, 0.0f, 0.0f, 0.0f}}}, {}, 1.0f});
                   pipeline.bind(cmd);
                   pipeline.push_descriptors<vert::Module, frag::Module>(cmd, vpl_bindings, gbuffer_bindings);
                   pipeline.push_constants(cmd, push);
                   vkCmdDrawIndirect(cmd, draw_args.buffer, draw_args.offset, 1, sizeof(VkDrawIndirectCommand));
                   end_rendering(cmd);
               });
    if (n == 1) return;

    namespace untile = shaders::flc_untile;
    const auto& untile_pipeline = device.pipeline<untile::Pipeline>();
    untile::Bindings untile_bindings;
    untile_bindings.tiled = tiled.descriptor();
    untile_bindings.gbuffer_position = gbuffer.position.descriptor();
    untile_bindings.gbuffer_geometric_normal = gbuffer.geometric_normal.descriptor();
    untile_bindings.indirect = indirect.descriptor();
    untile::Push untile_push{};
    untile_push.image_size = {indirect.width, indirect.height};
    untile_push.subtile_size = {side_x, side_y};
    untile_push.subtiles = n;
    untile_push.blur = options.blur ? 1u : 0u;
    untile_push.max_distance = gi_similarity_distance(options.blur_max_distance, scene_scale);
    untile_push.min_cos = options.blur_min_cos;
    const uint32_t w = indirect.width, h = indirect.height;
    add_dispatch<untile::Module>(passes, "flc untile", untile_pipeline, untile_bindings, untile_push, {w, h},
                                 {tiled, gbuffer.position, gbuffer.geometric_normal, indirect});
}

}  // namespace vplkit::stages

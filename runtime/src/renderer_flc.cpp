// The renderer's forward light cuts frame (the FLC paper): VPL candidates, the divergent triangles'
// subdivision, the stratified decimation (flc_stratify.comp, levels fitted to the scene's area),
// their compaction, the light at the kept VPLs, and the splatting raster pipeline into
// the indirect image. flc places its own VPLs (one per kept triangle), reads no VPL source and no
// tree, and is unshadowed one-bounce light, as in the paper.

#include "vplkit/renderer.hpp"

#include "frame_recording.hpp"

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/image.hpp"
#include "vplkit/planner.hpp"
#include "vplkit/stages/flc.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace vplkit {

void validate_flc_settings(const RenderSettings& settings) {
    if (settings.flc_levels < 1 || settings.flc_levels > stages::kFlcMaxLevels) {
        throw Error("flc: `flc_levels` " + std::to_string(settings.flc_levels) + " is outside 1.." +
                    std::to_string(stages::kFlcMaxLevels));
    }
    if (!std::isfinite(settings.flc_mu) || !(settings.flc_mu > 1.0f)) {
        throw Error("flc: `flc_mu` " + std::to_string(settings.flc_mu) + " must be finite and above 1");
    }
    if (!std::isfinite(settings.flc_vpls_per_point) || !(settings.flc_vpls_per_point > 0.0f)) {
        throw Error("flc: `flc_vpls_per_point` " + std::to_string(settings.flc_vpls_per_point) +
                    " must be finite and positive");
    }
    if (settings.flc_emitter_samples < 1) throw Error("flc: `flc_emitter_samples` must be at least 1");
    if (settings.flc_subtiles < 1 || settings.flc_subtiles > stages::kFlcMaxSubtiles) {
        throw Error("flc: `flc_subtiles` " + std::to_string(settings.flc_subtiles) + " is outside 1.." +
                    std::to_string(stages::kFlcMaxSubtiles));
    }
    if (settings.half_resolution_gi) {
        throw Error("flc: `half_resolution_gi` is not available: flc splats at the G-buffer's resolution");
    }
}

namespace {

// Eq. 1 with the scene radius: half the diagonal of the scene's box.
stages::FlcPartition flc_partition(const RenderSettings& settings, const scene::Bounds& bounds) {
    const float radius = 0.5f * glm::length(bounds.extent());
    return stages::flc_partition_for(radius, settings.flc_vpls_per_point, settings.flc_levels, settings.flc_mu);
}

// The triangles by the Morton code of their centroids (the stratified decimation's order), from
// the positions the GPU reads: fixed at first use, as the vertices' random integers are (the FLC paper
// sec. 6), so a triangle's stratum follows it when the scene moves.
std::vector<uint32_t> triangle_order(const scene::Scene& scene) {
    const std::vector<glm::vec3> corners = scene::triangle_positions(scene);
    std::vector<glm::vec3> centroids(corners.size() / 3);
    for (size_t t = 0; t < centroids.size(); ++t) {
        centroids[t] = (corners[3 * t] + corners[3 * t + 1] + corners[3 * t + 2]) / 3.0f;
    }
    return stages::flc_morton_order(centroids);
}

// Each triangle's area in double, from the positions the GPU reads (the subdivision's m).
std::vector<double> triangle_areas(const scene::Scene& scene) {
    const std::vector<glm::vec3> corners = scene::triangle_positions(scene);
    std::vector<double> areas(corners.size() / 3);
    for (size_t t = 0; t < areas.size(); ++t) {
        const glm::dvec3 a(corners[3 * t]), b(corners[3 * t + 1]), c(corners[3 * t + 2]);
        areas[t] = 0.5 * glm::length(glm::cross(b - a, c - a));
    }
    return areas;
}

}  // namespace

void Renderer::render_flc(const stages::CameraView& view, GbufferImages& gbuffer, const RenderSettings& settings,
                          Image& indirect, FrameRecording& frame, RenderedImage& out) {
    stages::FlcPartition partition = flc_partition(settings, scene_.bounds());
    const uint32_t triangles = scene_.triangle_count();
    if (flc_triangle_areas_.empty()) flc_triangle_areas_ = triangle_areas(scene_source_);
    if (flc_triangle_order_.empty()) flc_triangle_order_ = triangle_order(scene_source_);
    const stages::FlcSubdivision subdivision = [&] {
        try {
            return stages::flc_subdivision_for(flc_triangle_areas_, partition, stages::flc_max_candidates(context_));
        } catch (const Error& e) {
            // The stage speaks of its partition; name the settings that make it.
            throw Error(std::string(e.what()) + " (`flc_vpls_per_point`, `flc_levels`, `flc_mu`)");
        }
    }();
    const uint32_t candidate_count = triangles + subdivision.sub_count;
    // The levels are drawn by the stratified decimation, with S_k fitted to the scene's area.
    double scene_area = 0.0;
    for (double a : flc_triangle_areas_) scene_area += std::isfinite(a) ? a : 0.0;
    partition.scene_area = float(scene_area);
    const std::vector<uint32_t> order = stages::flc_candidate_order(flc_triangle_order_, subdivision, triangles);
    if (!flc_vertex_random_) {
        if (scene_source_.vertex_random.size() != scene_source_.vertices.size()) {
            throw Error(scene_source_.source.string() +
                        ": flc needs one random integer per vertex (scene::Scene::vertex_random), and the scene "
                        "has " +
                        std::to_string(scene_source_.vertex_random.size()) + " for " +
                        std::to_string(scene_source_.vertices.size()) + " vertices");
        }
        flc_vertex_random_ = Buffer::create(context_, scene_source_.vertex_random.size() * sizeof(uint32_t),
                                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "flc vertex random");
        flc_vertex_random_->upload(scene_source_.vertex_random);
    }
    // The frame's buffers, held until it has run.
    auto storage = [&](VkDeviceSize bytes, const char* name, VkBufferUsageFlags more = 0) -> Buffer& {
        return frame.hold(
            Buffer::create(context_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | more, MemoryUse::device, name));
    };
    const uint64_t n = candidate_count;
    Buffer& candidates = storage(n * sizeof(shaders::FlcCandidate), "flc candidates");
    Buffer& entries = storage(std::max<uint64_t>(subdivision.entries.size(), 1) * sizeof(shaders::FlcSubdivisionEntry),
                              "flc subdivision");
    if (!subdivision.entries.empty()) entries.upload(subdivision.entries);
    Buffer& albedo = storage(n * 4 * sizeof(float), "flc candidate albedo");
    Buffer& order_buffer = storage(n * sizeof(uint32_t), "flc order");
    order_buffer.upload(order);
    Buffer& carries = storage(partition.level_count * sizeof(float), "flc stratify carries");
    Buffer& counts = storage(stages::flc_count_bytes(partition.level_count), "flc counts");
    Buffer& kept = storage(n * sizeof(uint32_t), "flc kept triangles");
    Buffer& divergent = storage(n * sizeof(uint32_t), "flc divergent triangles");
    Buffer& vpls = storage(n * sizeof(shaders::Vpl), "flc vpls");
    Buffer& draw_args = storage(stages::kFlcDrawArgsBytes, "flc draw args", VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);

    // Interleaved sub-tiles: the splat's target, n sub-tiles of ceil(size / n) each way.
    stages::FlcSplatOptions splat_options;
    splat_options.subtiles = settings.flc_subtiles;
    std::optional<Image>& tiled = frame.hold(std::optional<Image>());
    if (splat_options.subtiles > 1) {
        const uint32_t n = splat_options.subtiles;
        tiled.emplace(Image::create(context_, n * stages::flc_subtile_side(gbuffer.width(), n),
                                    n * stages::flc_subtile_side(gbuffer.height(), n), stages::kFlcIndirectFormat,
                                    VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT, "flc sub-tiles"));
    }

    PassList& passes = frame.passes();
    passes.set_tag(stage_tag(FrameStage::flc_vpls));
    stages::add_flc_candidates_pass(
        context_, passes, {scene_.vertices(), scene_.indices(), *flc_vertex_random_, candidates, scene_.addressed()},
        partition, triangles, settings.seed);
    stages::add_flc_subdivide_pass(context_, passes,
                                   {scene_.vertices(), scene_.indices(), *flc_vertex_random_, entries, candidates,
                                    vpl_sources().triangle_albedo, albedo, scene_.addressed()},
                                   partition, subdivision, triangles, settings.seed);
    stages::add_flc_stratify_passes(context_, passes, {candidates, order_buffer, carries}, partition, candidate_count,
                                    settings.seed);
    stages::add_flc_compact_passes(context_, passes, {candidates, counts, kept, divergent}, partition.level_count,
                                   candidate_count);
    stages::add_flc_vpl_light_pass(context_, passes, gpu_bvh(), lights_, emitters_,
                                   {candidates, counts, kept, albedo, vpls}, partition, candidate_count,
                                   {settings.flc_emitter_samples, settings.seed});
    passes.set_tag(stage_tag(FrameStage::gi_flc));
    stages::add_flc_splat_passes(context_, passes, {candidates, counts, kept, vpls, draw_args}, gbuffer, indirect, view,
                                 partition, candidate_count, gpu_bvh().scene_scale, splat_options,
                                 tiled ? ImageView(*tiled) : ImageView{});
    out.gi_width = gbuffer.width();
    out.gi_height = gbuffer.height();
    frame.after_run([&out, &counts, triangles, subs = subdivision.sub_count] {
        const auto count = counts.download<uint32_t>(2);
        out.vpl_count = count[0];
        out.notes.push_back("flc: " + std::to_string(count[0]) + " VPLs kept of " + std::to_string(triangles) +
                            " triangles and " + std::to_string(subs) + " sub-triangles of " + std::to_string(count[1]) +
                            " divergent ones");
        if (count[0] == 0) out.notes.push_back("flc: no triangle was kept: no indirect light");
    });
}

}  // namespace vplkit

// Renderer::update_pose: a new pose of the scene's vertices and lights uploaded, the BVH refitted
// (or rebuilt) on the GPU, and the version the planner compares its caches' against moved on.
// Renderer::pose: the scene posed first, its moving vertices on the host or on the GPU. On the
// GPU they stay there: the pose pass writes GpuScene's vertex buffer and the BVH is refitted from
// it in the same submission; the host scene takes them only where a host reader needs them.

#include "vplkit/renderer.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gpu_pose.hpp"

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace vplkit {

namespace {

double half_area(const shaders::BvhNode& node) {
    const double dx = std::max(0.0, double(node.hi.x) - node.lo.x);
    const double dy = std::max(0.0, double(node.hi.y) - node.lo.y);
    const double dz = std::max(0.0, double(node.hi.z) - node.lo.z);
    return dx * dy + dy * dz + dz * dx;
}

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::string format_ms(double ms) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f ms", ms);
    return text;
}

// What the host computes from a pose's vertices, which a GPU pose then reads back into the host
// scene ("" when nothing does: the pose stays on the GPU): the emitters and light trees built
// from emissive triangles, the VPL sources' disc over the scene's bounding sphere and the shadow
// maps fitted to its bounds for directional lights, forward light cuts' triangle areas and order
// (once that method has run: `flc_used`).
std::string host_readers_of_vertices(const scene::Scene& scene, bool flc_used) {
    std::string readers;
    const auto add = [&](const char* what) { readers += (readers.empty() ? "" : ", ") + std::string(what); };
    if (!scene.emissive_triangles.empty()) add("the emissive triangles");
    if (!directional_lights(scene).empty()) add("the directional lights' bounds");
    if (flc_used) add("forward light cuts' triangle areas");
    return readers;
}

// The box of the indexed vertices, as GpuScene::update_vertices computes it.
scene::Bounds indexed_bounds(const scene::Scene& scene) {
    scene::Bounds bounds;
    bounds.min = bounds.max = scene.vertices.at(scene.indices.at(0)).position;
    for (uint32_t index : scene.indices) {
        bounds.min = glm::min(bounds.min, scene.vertices[index].position);
        bounds.max = glm::max(bounds.max, scene.vertices[index].position);
    }
    return bounds;
}

// A BVH's root box: the posed triangles' bounds, padded (conservative).
scene::Bounds root_bounds(const shaders::BvhNode& root) {
    scene::Bounds bounds;
    bounds.min = glm::vec3(root.lo.x, root.lo.y, root.lo.z);
    bounds.max = glm::vec3(root.hi.x, root.hi.y, root.hi.z);
    return bounds;
}

}  // namespace

double bvh_sah_cost(std::span<const shaders::BvhNode> nodes) {
    if (nodes.empty()) return 0.0;
    const double root = half_area(nodes[0]);
    if (!(root > 0.0)) return 0.0;
    double cost = 0.0;
    for (const shaders::BvhNode& node : nodes) {
        cost += half_area(node) * (bvh_is_leaf(node) ? double(bvh_leaf_triangles(node)) : 1.0);
    }
    return cost / root;
}

void Renderer::build_moving_bvh(std::span<const glm::vec3> positions) {
    // The alpha-test records the host build made (bvh_.alpha, BvhTriangle::alpha per triangle id)
    // depend on materials and UVs only: the GPU build takes them as they are.
    GpuBvhAlphaRecords alpha;
    const GpuBvhAlphaRecords* records = nullptr;
    if (!bvh_.alpha.empty()) {
        alpha.words = bvh_.alpha;
        alpha.triangle_records.assign(positions.size() / 3, 0u);
        for (const shaders::BvhTriangle& t : bvh_.triangles) alpha.triangle_records.at(t.id) = t.alpha;
        records = &alpha;
    }
    moving_bvh_.reset();  // its buffers freed before the new ones are made
    moving_bvh_.emplace(context_, positions, std::span<const uint32_t>{}, stages::BvhGpuBuildOptions{}, records);
    const GpuBvh& built = moving_bvh_->bvh();
    moving_bvh_built_cost_ = bvh_sah_cost(built.nodes.download<shaders::BvhNode>(built.node_count));
}

PoseUpdate Renderer::update_pose(const scene::PoseChange& change) {
    const scene::Scene& scene = scene_source_;
    PoseUpdate update;
    std::string summary;
    if (change.vertices) {
        host_pose_stale_ = false;  // the caller moved the host scene: it is the pose from now on
        const auto upload_start = std::chrono::steady_clock::now();
        scene_.update_vertices(scene);  // throws for another vertex or triangle count
        if (!scene.emissive_triangles.empty()) emitters_ = upload_emitters(context_, scene);
        update.upload_ms = ms_since(upload_start);

        const auto bvh_start = std::chrono::steady_clock::now();
        const std::vector<glm::vec3> positions = scene::triangle_positions(scene);
        if (!moving_bvh_) {
            build_moving_bvh(positions);
            update.bvh = BvhUpdate::rebuild;
            summary = "BVH built on the GPU (the first move; the host's build served the still scene)";
        } else {
            moving_bvh_->refit(positions);
            const GpuBvh& refitted = moving_bvh_->bvh();
            const double cost = bvh_sah_cost(refitted.nodes.download<shaders::BvhNode>(refitted.node_count));
            update.bvh_cost_ratio = moving_bvh_built_cost_ > 0.0 ? cost / moving_bvh_built_cost_ : 1.0;
            update.bvh = BvhUpdate::refit;
            char ratio[64];
            std::snprintf(ratio, sizeof ratio, "%.3gx", update.bvh_cost_ratio);
            summary = std::string("BVH refitted on the GPU (SAH cost ") + ratio + " its build's)";
            if (update.bvh_cost_ratio > kBvhRebuildCostRatio) {
                update.refit_cost_ratio = update.bvh_cost_ratio;
                build_moving_bvh(positions);
                update.bvh = BvhUpdate::rebuild;
                update.bvh_cost_ratio = 1.0;
                std::snprintf(ratio, sizeof ratio, "%.3gx", kBvhRebuildCostRatio);
                summary =
                    "BVH rebuilt on the GPU (refitted, its SAH cost was " + summary.substr(summary.find('(') + 10);
                summary.pop_back();
                summary += ", past " + std::string(ratio) + ")";
            }
        }
        update.bvh_gpu_ms = moving_bvh_->stats().gpu_ms;
        update.bvh_ms = ms_since(bvh_start);
        // What was computed once from the positions: forward light cuts' areas and order.
        flc_triangle_areas_.clear();
        flc_triangle_order_.clear();
        ++version_.geometry;
        update.geometry = true;
        summary = "geometry moved: " + std::to_string(scene.vertices.size()) + " vertices uploaded (" +
                  format_ms(update.upload_ms) + "), " + summary + " (" + format_ms(update.bvh_ms) + ")";
    }
    if (change.lights) {
        const auto start = std::chrono::steady_clock::now();
        lights_ = upload_lights(context_, scene.lights);
        directional_lights_ = upload_lights(context_, directional_lights(scene));
        update.upload_ms += ms_since(start);
        ++version_.lights;
        update.lights = true;
        summary += std::string(summary.empty() ? "" : "; ") + "lights moved: " + std::to_string(scene.lights.size()) +
                   " light(s) uploaded";
    }
    if (update.geometry || update.lights) {
        // The VPL tracer's copy of the lights and emitters; the mean of a still camera's frames.
        vpl_sources_.reset();
        accumulator_ = FrameAccumulator{};
        // An SMC set lives on: its next update drops VPLs the geometry left and estimates the rest again.
        if (smc_) smc_->scene_moved(update.geometry, update.lights);
    }
    update.summary = summary.empty() ? "" : "pose: " + summary;
    pose_note_ = update.summary;
    return update;
}

PoseUpdate Renderer::pose(scene::PosableScene& posable, double time, PosePath path) {
    if (&posable.scene() != &scene_source_) {
        throw Error("Renderer::pose: the posable scene is not the one this renderer was made with");
    }
    bool on_gpu = path == PosePath::gpu;
    if (path == PosePath::automatic) {
        // The pose pass binds its buffers whole: a scene past one binding's range poses on the host.
        const scene::VertexPoseRest& rest = posable.vertex_pose_rest();
        const uint64_t range = context_.info().max_storage_buffer_range;
        const auto within_range = [range](size_t count, size_t element) { return count * element <= range; };
        on_gpu = posable.vertex_pose_refusal().empty() && rest.vertices.size() >= size_t(kGpuPoseMinVertices) &&
                 !scene_.addressed() && within_range(rest.vertices.size(), sizeof(shaders::PoseRestVertex)) &&
                 within_range(rest.deltas.size(), sizeof(shaders::MorphDelta));
    }
    const auto start = std::chrono::steady_clock::now();
    if (!on_gpu) {
        host_pose_stale_ = false;  // every vertex is posed again on the host
        const scene::PoseChange change = posable.pose(time);
        const double pose_ms = ms_since(start);
        PoseUpdate update = update_pose(change);
        update.pose_ms = pose_ms;
        return update;
    }
    scene::VertexPoseFrame frame;
    const scene::PoseChange change = posable.pose_nodes(time, frame);  // Error naming a refusal
    if (!change.vertices) {
        PoseUpdate update = update_pose(change);
        update.pose_ms = ms_since(start);
        update.posed_on_gpu = true;
        return update;
    }
    if (!gpu_pose_) gpu_pose_.emplace(context_, posable.vertex_pose_rest());
    gpu_pose_->set_frame(frame);
    // One submission: the pose written into the scene's vertex buffer, the BVH refitted from it.
    PassList passes("gpu pose");
    const BufferView vertices = scene_.begin_device_pose(passes);
    gpu_pose_->add_pose_pass(passes, vertices);
    const bool refit = moving_bvh_.has_value();
    const bool device_refit = refit && moving_bvh_->refits_from_device();
    if (device_refit) moving_bvh_->add_refit_passes(passes, vertices, scene_.indices());
    passes.run(context_);
    PoseUpdate update;
    for (const PassTiming& timing : passes.timings()) {
        const bool pose = timing.name == "pose vertices" || timing.name == "scene vertices copy";
        (pose ? update.pose_gpu_ms : update.bvh_gpu_ms) += timing.gpu_ms;
    }
    update.pose_ms = ms_since(start);

    // Read back only for what the host computes from vertices (host_readers_of_vertices), and
    // for a BVH build (its checks and the triangles it leaves out are the host's).
    std::vector<scene::Vertex> posed;
    const auto read_back = [&] {
        if (posed.empty()) posed = scene_.vertices().download<scene::Vertex>(scene_.vertex_count());
    };
    const auto posed_positions = [&] {
        read_back();
        std::vector<glm::vec3> positions;
        positions.reserve(scene_source_.indices.size());
        for (uint32_t index : scene_source_.indices) positions.push_back(posed.at(index).position);
        return positions;
    };
    const std::string for_host = host_readers_of_vertices(scene_source_, flc_vertex_random_.has_value());
    const auto upload_start = std::chrono::steady_clock::now();
    host_pose_stale_ = for_host.empty();
    if (!for_host.empty()) {
        read_back();
        posable.take_posed_vertices(posed);  // the scene's bounds follow
        if (!scene_source_.emissive_triangles.empty()) emitters_ = upload_emitters(context_, scene_source_);
    }
    update.upload_ms = ms_since(upload_start);

    const auto bvh_start = std::chrono::steady_clock::now();
    std::string summary;
    shaders::BvhNode root{};
    if (!refit) {
        build_moving_bvh(posed_positions());
        update.bvh = BvhUpdate::rebuild;
        update.bvh_gpu_ms = moving_bvh_->stats().gpu_ms;
        summary = "BVH built on the GPU from the posed vertices read back (the first move)";
    } else {
        if (device_refit) {
            moving_bvh_->finish_refit(update.bvh_gpu_ms);
        } else {
            moving_bvh_->refit(posed_positions());  // a BVH read at its addresses: from the host
            update.bvh_gpu_ms = moving_bvh_->stats().gpu_ms;
        }
        const GpuBvh& refitted = moving_bvh_->bvh();
        const std::vector<shaders::BvhNode> nodes = refitted.nodes.download<shaders::BvhNode>(refitted.node_count);
        root = nodes.at(0);
        const double cost = bvh_sah_cost(nodes);
        update.bvh_cost_ratio = moving_bvh_built_cost_ > 0.0 ? cost / moving_bvh_built_cost_ : 1.0;
        update.bvh = BvhUpdate::refit;
        char ratio[64];
        std::snprintf(ratio, sizeof ratio, "%.3g", update.bvh_cost_ratio);
        summary = std::string("BVH refitted on the GPU") + (device_refit ? " from the posed vertices" : "") +
                  " (SAH cost " + ratio + "x its build's)";
        if (update.bvh_cost_ratio > kBvhRebuildCostRatio) {
            update.refit_cost_ratio = update.bvh_cost_ratio;
            build_moving_bvh(posed_positions());
            update.bvh = BvhUpdate::rebuild;
            update.bvh_cost_ratio = 1.0;
            update.bvh_gpu_ms += moving_bvh_->stats().gpu_ms;
            std::snprintf(ratio, sizeof ratio, "%.3g", update.refit_cost_ratio);
            summary = std::string(
                          "BVH rebuilt on the GPU from the posed vertices read back (refitted, its SAH cost "
                          "was ") +
                      ratio + "x its build's)";
        }
    }
    if (update.bvh == BvhUpdate::rebuild) root = moving_bvh_->bvh().nodes.download<shaders::BvhNode>(1).at(0);
    // The raster stages' scene bounds (shadow maps, forward light cuts' partition).
    scene_.set_bounds(for_host.empty() ? root_bounds(root) : indexed_bounds(scene_source_));
    update.bvh_ms = ms_since(bvh_start);
    // What update_pose does after its upload: forward light cuts' areas and order go, the
    // version moves on, the lights (if they moved) are uploaded and the caches reset.
    flc_triangle_areas_.clear();
    flc_triangle_order_.clear();
    ++version_.geometry;
    vpl_sources_.reset();
    accumulator_ = FrameAccumulator{};
    if (smc_) smc_->scene_moved(true, false);
    scene::PoseChange rest = change;
    rest.vertices = false;
    const PoseUpdate lights = update_pose(rest);
    update.lights = lights.lights;
    update.upload_ms += lights.upload_ms;
    update.geometry = true;
    update.posed_on_gpu = true;
    update.summary =
        "pose: geometry moved, posed on the GPU: " + std::to_string(gpu_pose_->vertex_count()) + " vertices (" +
        format_ms(update.pose_ms) + ")" +
        (for_host.empty() ? ", the host scene left as it was" : ", read back into the host scene for " + for_host) +
        ", " + summary + " (" + format_ms(update.bvh_ms) + ")";
    if (!lights.summary.empty()) update.summary += "; " + lights.summary.substr(6);  // without its "pose: "
    pose_note_ = update.summary;
    return update;
}

void Renderer::read_pose_back(scene::PosableScene& posable) {
    if (&posable.scene() != &scene_source_) {
        throw Error("Renderer::read_pose_back: the posable scene is not the one this renderer was made with");
    }
    if (!host_pose_stale_) return;
    posable.take_posed_vertices(scene_.vertices().download<scene::Vertex>(scene_.vertex_count()));
    host_pose_stale_ = false;
}

}  // namespace vplkit

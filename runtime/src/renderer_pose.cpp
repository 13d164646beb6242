// Renderer::update_pose: a new pose of the scene's vertices and lights uploaded, the BVH refitted
// (or rebuilt) on the GPU, and the version the planner compares its caches' against moved on.
// Renderer::pose: the scene posed first, its moving vertices on the host or on the GPU.

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
        on_gpu = posable.vertex_pose_refusal().empty() &&
                 posable.vertex_pose_rest().vertices.size() >= size_t(kGpuPoseMinVertices);
    }
    const auto start = std::chrono::steady_clock::now();
    if (!on_gpu) {
        const scene::PoseChange change = posable.pose(time);
        const double pose_ms = ms_since(start);
        PoseUpdate update = update_pose(change);
        update.pose_ms = pose_ms;
        return update;
    }
    scene::VertexPoseFrame frame;
    const scene::PoseChange change = posable.pose_nodes(time, frame);  // Error naming a refusal
    double gpu_ms = 0.0;
    if (change.vertices) {
        const std::vector<scene::Vertex>& vertices = scene_source_.vertices;
        if (!gpu_pose_) {
            gpu_pose_.emplace(context_, posable.vertex_pose_rest());
            gpu_posed_vertices_ =
                Buffer::create(context_, vertices.size() * sizeof(scene::Vertex), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                               MemoryUse::device, "gpu-posed vertices");
            gpu_posed_vertices_.upload(vertices);  // what does not move stays as loaded
        }
        gpu_pose_->set_frame(frame);
        PassList passes("gpu pose");
        gpu_pose_->add_pose_pass(passes, gpu_posed_vertices_);
        passes.run(context_);
        gpu_ms = passes.total_gpu_ms();
        // The host scene takes the pose, so the upload, the BVH and every host reader follow it.
        posable.take_posed_vertices(gpu_posed_vertices_.download<scene::Vertex>(vertices.size()));
    }
    const double pose_ms = ms_since(start);
    PoseUpdate update = update_pose(change);
    update.pose_ms = pose_ms;
    update.posed_on_gpu = true;
    update.pose_gpu_ms = gpu_ms;
    if (change.vertices) {
        update.summary += " (posed on the GPU: " + std::to_string(gpu_pose_->vertex_count()) + " vertices, " +
                          format_ms(pose_ms) + ")";
        pose_note_ = update.summary;
    }
    return update;
}

}  // namespace vplkit

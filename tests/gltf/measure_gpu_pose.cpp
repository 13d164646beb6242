// Not a test: the per-frame cost of posing a file's vertices on the host (PosableScene::pose,
// then the upload GpuScene::update_vertices makes) against posing them on the GPU
// (PosableScene::pose_nodes, GpuPose::set_frame, one "pose vertices" pass, submitted and waited
// for), frames interleaved host, GPU, host, ... and medians printed. Scenes: the deforming set-up
// and skinned_tube at a size given on the command line (rings x (sides + 1) vertices). Then the
// whole geometry update through Renderer::pose on each path (pose, upload, BVH refit).
//
//   measure_gpu_pose [frames] [rings] [sides] [deforming_box.gltf]
//   (defaults 24, 317, 315: 100,488 tube vertices; the file in this repository's scenes/)
//   VPLKIT_DEVICE picks the device (lavapipe unless a GPU is present).

#include "skinned_tube.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/gpu_pose.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene_pose.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values.empty() ? 0.0 : values[values.size() / 2];
}

void measure(vplkit::Context& context, const std::string& name, const fs::path& file, uint32_t frames,
             double duration) {
    vplkit::scene::PosableScene host(file), gpu(file);
    if (!gpu.vertex_pose_refusal().empty()) {
        std::printf("%s: %s\n", name.c_str(), gpu.vertex_pose_refusal().c_str());
        return;
    }
    const auto& vertices = host.scene().vertices;
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
    vplkit::Buffer host_buffer = vplkit::Buffer::create(context, vertices.size() * sizeof(vertices[0]), usage,
                                                        vplkit::MemoryUse::device, "host-posed vertices");
    vplkit::Buffer gpu_buffer = vplkit::Buffer::create(context, vertices.size() * sizeof(vertices[0]), usage,
                                                       vplkit::MemoryUse::device, "gpu-posed vertices");
    gpu_buffer.upload(gpu.scene().vertices);
    const auto setup_start = Clock::now();
    vplkit::GpuPose pose(context, gpu.vertex_pose_rest());
    const double setup_ms = ms_since(setup_start);

    std::vector<double> host_pose, host_upload, gpu_nodes, gpu_run, gpu_pass;
    vplkit::scene::VertexPoseFrame frame;
    for (uint32_t f = 0; f <= frames; ++f) {
        const double t = duration * f / frames + 0.01;  // never the rest pose
        auto start = Clock::now();
        host.pose(t);
        const double pose_ms = ms_since(start);
        start = Clock::now();
        host_buffer.upload(host.scene().vertices);
        const double upload_ms = ms_since(start);

        start = Clock::now();
        gpu.pose_nodes(t, frame);
        const double nodes_ms = ms_since(start);
        start = Clock::now();
        pose.set_frame(frame);
        vplkit::PassList passes("measure pose");
        pose.add_pose_pass(passes, gpu_buffer);
        passes.run(context);
        const double run_ms = ms_since(start);
        if (f == 0) continue;  // pipelines made on first use
        host_pose.push_back(pose_ms);
        host_upload.push_back(upload_ms);
        gpu_nodes.push_back(nodes_ms);
        gpu_run.push_back(run_ms);
        gpu_pass.push_back(passes.total_gpu_ms());
    }
    std::printf("%-14s %8zu %8zu | %9.3f %9.3f %9.3f | %9.3f %9.3f %9.3f %9.3f | %8.1f\n", name.c_str(),
                vertices.size(), gpu.vertex_pose_rest().vertices.size(), median(host_pose), median(host_upload),
                median(host_pose) + median(host_upload), median(gpu_nodes), median(gpu_run), median(gpu_pass),
                median(gpu_nodes) + median(gpu_run), setup_ms);
}

// The whole geometry update of a frame through Renderer::pose on each path: the pose, the
// vertices' upload, the BVH refit (rebuilds counted apart), and their sum. The GPU path records
// the pose and the refit in one submission: its "pose" holds the refit's GPU work, "BVH refit"
// what follows it on the host (the node count and SAH cost read back).
void measure_renderer(vplkit::Context& context, const std::string& name, const fs::path& file, uint32_t frames,
                      double duration) {
    vplkit::scene::PosableScene host_scene(file), gpu_scene(file);
    vplkit::Renderer host(context, host_scene.scene()), gpu(context, gpu_scene.scene());
    // Per path: pose, upload, BVH (refit frames only: a rebuild is counted apart).
    std::vector<double> times[2][5];
    for (uint32_t f = 0; f <= frames; ++f) {
        const double t = duration * f / frames + 0.01;
        const vplkit::PoseUpdate updates[2] = {host.pose(host_scene, t, vplkit::PosePath::host),
                                               gpu.pose(gpu_scene, t, vplkit::PosePath::gpu)};
        if (f == 0 || updates[0].bvh != vplkit::BvhUpdate::refit || updates[1].bvh != vplkit::BvhUpdate::refit)
            continue;
        for (int p = 0; p < 2; ++p) {
            times[p][0].push_back(updates[p].pose_ms);
            times[p][1].push_back(updates[p].upload_ms);
            times[p][2].push_back(updates[p].bvh_ms);
            times[p][3].push_back(updates[p].bvh_gpu_ms);
            times[p][4].push_back(updates[p].pose_ms + updates[p].upload_ms + updates[p].bvh_ms);
        }
    }
    for (int p = 0; p < 2; ++p) {
        std::printf(
            "%-14s Renderer::pose on the %s, %zu refit frames: pose %.3f, upload %.3f, BVH refit %.3f (GPU %.3f), "
            "whole update %.3f\n",
            name.c_str(), p == 0 ? "host" : "GPU ", times[p][0].size(), median(times[p][0]), median(times[p][1]),
            median(times[p][2]), median(times[p][3]), median(times[p][4]));
    }
}

}  // namespace

int main(int argc, char** argv) {
    const uint32_t frames = argc > 1 ? uint32_t(std::atoi(argv[1])) : 24;
    const uint32_t rings = argc > 2 ? uint32_t(std::atoi(argv[2])) : 317;
    const uint32_t sides = argc > 3 ? uint32_t(std::atoi(argv[3])) : 315;
    if (frames < 1 || rings < 2 || sides < 3) {
        std::fprintf(stderr, "usage: measure_gpu_pose [frames>=1] [rings>=2] [sides>=3]\n");
        return 2;
    }
    auto owned = vplkit::Context::create({});
    vplkit::Context& context = *owned;
    std::printf("device: %s; %u frames each, interleaved; medians in ms\n", context.info().name.c_str(), frames);
    std::printf("%-14s %8s %8s | %9s %9s %9s | %9s %9s %9s %9s | %8s\n", "scene", "vertices", "posed", "host pose",
                "upload", "host sum", "nodes", "gpu run", "gpu pass", "gpu sum", "setup");
    const fs::path deforming =
        argc > 4 ? fs::path(argv[4])
                 : fs::path(scene_test::source_dir()) / "scenes" / "deforming_box" / "deforming_box.gltf";
    measure(context, "deforming-box", deforming, frames, 4.0);
    scene_test::TempDir dir("measure_gpu_pose");
    const fs::path tube = gltf_features::skinned_tube(rings, sides).write(dir.path(), "tube", false);
    measure(context, "skinned tube", tube, frames, 2.0);
    measure_renderer(context, "deforming-box", deforming, frames, 4.0);
    measure_renderer(context, "skinned tube", tube, frames, 2.0);
    return 0;
}

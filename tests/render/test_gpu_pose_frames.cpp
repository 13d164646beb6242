// Renderer::pose on the GPU path against the host path: the deforming set-up (a skinned reed, a
// morph-target panel) followed over three frames by two renderers, one posing on the host
// (PosableScene::pose) and one on the GPU (pose_nodes, "pose vertices" into the scene's vertex
// buffer, the BVH refitted from it: no vertex read back, the host scene stays at rest). The frames
// must agree to float rounding (the GPU poses in float what the host poses in double: vertices
// within 2e-7 relative, tests/gltf/test_gpu_pose), and the pose must show in the image.
//
// Tolerance: no pixel differs by more than 1e-4 of the brightest (direct light, exact gather
// over the same IR VPLs: the same seed traces the same paths over triangles a few ulps apart).

#include "vplkit/error.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene_pose.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

namespace {

namespace fs = std::filesystem;

fs::path deforming_box() {
    return fs::path(VPLKIT_SOURCE_DIR) / "scenes" / "deforming_box" / "deforming_box.gltf";
}

// The largest difference of a channel over the largest value of `reference`.
double relative_difference(const std::vector<float>& image, const std::vector<float>& reference) {
    REQUIRE(image.size() == reference.size());
    double largest = 0.0, worst = 0.0;
    for (size_t i = 0; i < image.size(); ++i) {
        largest = std::max(largest, double(reference[i]));
        worst = std::max(worst, std::fabs(double(image[i]) - reference[i]));
    }
    return largest > 0.0 ? worst / largest : 0.0;
}

}  // namespace

TEST_CASE("gpu pose: the deforming set-up's frames posed on the GPU equal the host-posed frames") {
    vplkit::Context& ctx = vplkit::test::context();
    vplkit::scene::PosableScene host_scene(deforming_box()), gpu_scene(deforming_box());
    vplkit::Renderer host(ctx, host_scene.scene()), gpu(ctx, gpu_scene.scene());
    vplkit::RenderSettings settings;
    settings.width = settings.height = 64;
    settings.method = vplkit::GiMethod::exact;
    settings.vpl_source = vplkit::VplSource::ir;
    settings.vpl_paths = 256;
    const vplkit::scene::Camera camera = host_scene.scene().cameras.at(host_scene.scene().active_camera);
    const std::vector<float> rest = host.render(camera, settings).radiance;
    // Nothing on the host reads this scene's posed vertices (a point light, no emissive triangle,
    // no forward light cuts): the GPU path leaves them on the GPU, the host scene at rest.
    const std::vector<vplkit::scene::Vertex> rest_vertices = gpu_scene.scene().vertices;
    const auto at_rest = [&] {
        const auto& now = gpu_scene.scene().vertices;
        return now.size() == rest_vertices.size() &&
               std::equal(now.begin(), now.end(), rest_vertices.begin(), [](const auto& a, const auto& b) {
                   return a.position == b.position && a.normal == b.normal && a.tangent == b.tangent;
               });
    };
    for (double t : {0.5, 1.25, 2.0}) {
        CAPTURE(t);
        const vplkit::PoseUpdate by_host = host.pose(host_scene, t, vplkit::PosePath::host);
        const vplkit::PoseUpdate by_gpu = gpu.pose(gpu_scene, t, vplkit::PosePath::gpu);
        CHECK_FALSE(by_host.posed_on_gpu);
        CHECK(by_gpu.posed_on_gpu);
        CHECK(by_gpu.geometry);
        CHECK(by_gpu.bvh == by_host.bvh);
        CHECK(at_rest());
        CHECK(by_gpu.summary.find("the host scene left as it was") != std::string::npos);
        // Only a BVH build (the first move here) reads the posed positions back; a refit does not.
        if (by_gpu.bvh == vplkit::BvhUpdate::refit) CHECK(by_gpu.summary.find("read back") == std::string::npos);
        const auto host_frame = host.render(camera, settings);
        const auto gpu_frame = gpu.render(camera, settings);
        const double difference = relative_difference(gpu_frame.radiance, host_frame.radiance);
        CHECK(difference <= 1e-4);
        // The pose shows: 0.009 of the brightest at 0.5 s, more later.
        CHECK(relative_difference(host_frame.radiance, rest) > 1e-3);
        MESSAGE("t = ", t, ": GPU-posed frame against host-posed, ", difference, " of the brightest");
    }
    // A reader outside the renderer (the CLI's reference renderer) takes the pose on request.
    gpu.read_pose_back(gpu_scene);
    CHECK_FALSE(at_rest());
    const auto& taken = gpu_scene.scene().vertices;
    const auto& by_host = host_scene.scene().vertices;
    REQUIRE(taken.size() == by_host.size());
    float worst = 0.0f;
    for (size_t i = 0; i < taken.size(); ++i) {
        worst = std::max(worst, glm::length(taken[i].position - by_host[i].position));
    }
    CHECK(worst < 1e-5f);
    // The automatic path leaves these 193 moving vertices to the host (under kGpuPoseMinVertices).
    CHECK_FALSE(gpu.pose(gpu_scene, 2.5).posed_on_gpu);
    // Another scene than the renderer's is refused.
    vplkit::scene::PosableScene other(deforming_box());
    CHECK_THROWS_AS(gpu.pose(other, 1.0), vplkit::Error);
}

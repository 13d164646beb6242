// Vertices posed on the GPU (pose_vertices.comp through GpuPose) against the host pose
// (PosableScene::pose, the loader's own morphing and skinning in double precision): positions,
// normals and tangents of every vertex at several times, on the deforming set-up (a skinned reed,
// a morph-target panel) and on skinned_tube (a third joint influence, weights rescaled, morphed
// normals and tangents, alternating handedness, a mirrored rigid quad that turns).
//
// Tolerance 1e-5 relative (of max(1, |host value|)): the GPU blends and transforms in float where
// the host works in double, an error of a few float ulps on values of order 1.

#include "animation_files.hpp"
#include "skinned_tube.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gpu_pose.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene_pose.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using vplkit::scene::PosableScene;
using vplkit::scene::Vertex;

fs::path deforming_box() {
    return fs::path(scene_test::source_dir()) / "scenes" / "deforming_box" / "deforming_box.gltf";
}

float relative_error(glm::vec4 gpu, glm::vec4 host) {
    return glm::length(gpu - host) / std::max(1.0f, glm::length(host));
}

struct Worst {
    float position = 0.0f, normal = 0.0f, tangent = 0.0f;
};

// Poses `host` with PosableScene::pose and `gpu` with pose_nodes + GpuPose at each time, and
// returns the largest differences over every vertex and time.
Worst compare_poses(const fs::path& file, const std::vector<double>& times) {
    vplkit::Context& context = vplkit::test::context();
    PosableScene host(file), gpu(file);
    REQUIRE(gpu.vertex_pose_refusal().empty());
    REQUIRE(!gpu.vertex_pose_rest().vertices.empty());
    const std::vector<Vertex>& loaded = gpu.scene().vertices;
    vplkit::Buffer vertices =
        vplkit::Buffer::create(context, loaded.size() * sizeof(Vertex), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                               vplkit::MemoryUse::device, "scene vertices");
    vertices.upload(loaded);
    vplkit::GpuPose pose(context, gpu.vertex_pose_rest());
    Worst worst;
    for (double t : times) {
        CAPTURE(t);
        const vplkit::scene::PoseChange host_change = host.pose(t);
        vplkit::scene::VertexPoseFrame frame;
        const vplkit::scene::PoseChange gpu_change = gpu.pose_nodes(t, frame);
        CHECK(gpu_change.lights == host_change.lights);
        CHECK(gpu_change.cameras == host_change.cameras);
        CHECK(gpu.scene().time == host.scene().time);
        pose.set_frame(frame);
        vplkit::PassList passes("gpu pose test");
        pose.add_pose_pass(passes, vertices);
        passes.run(context);
        const std::vector<Vertex> posed = vertices.download<Vertex>(loaded.size());
        const std::vector<Vertex>& expected = host.scene().vertices;
        REQUIRE(posed.size() == expected.size());
        for (size_t v = 0; v < posed.size(); ++v) {
            worst.position = std::max(
                worst.position, relative_error(glm::vec4(posed[v].position, 0), glm::vec4(expected[v].position, 0)));
            worst.normal =
                std::max(worst.normal, relative_error(glm::vec4(posed[v].normal, 0), glm::vec4(expected[v].normal, 0)));
            worst.tangent = std::max(worst.tangent, relative_error(posed[v].tangent, expected[v].tangent));
            // What the pose does not touch stays as loaded.
            CHECK(posed[v].uv0 == expected[v].uv0);
            CHECK(posed[v].color == expected[v].color);
        }
    }
    return worst;
}

}  // namespace

TEST_CASE("gpu pose: the deforming set-up's reed and panel posed on the GPU equal the host's pose") {
    PosableScene posable(deforming_box());
    // The reed (72 vertices) and the panel (121) move; the box and the block do not.
    CHECK(posable.vertex_pose_rest().vertices.size() == 72 + 121);
    CHECK(posable.vertex_pose_rest().instances.size() == 2);
    const Worst worst = compare_poses(deforming_box(), {0.4, 1.0, 1.7, 2.0, 3.3, 1.0});
    CHECK(worst.position <= 1e-5f);
    CHECK(worst.normal <= 1e-5f);
    CHECK(worst.tangent <= 1e-5f);
    MESSAGE("deforming box, GPU against host: position ", worst.position, ", normal ", worst.normal);
}

TEST_CASE("gpu pose: a skinned, morphed tube with tangents and a mirrored turning quad equal the host's pose") {
    scene_test::TempDir dir("gpu_pose_tube");
    const fs::path file = gltf_features::skinned_tube(12, 10).write(dir.path(), "tube", true);
    PosableScene posable(file);
    CHECK(posable.vertex_pose_rest().vertices.size() == 12 * 11 + 4);
    CHECK(posable.vertex_pose_rest().deltas.size() == 12 * 11);
    // Times between keys, on keys, and past the last (clamped); the STEP channel jumps at 1 s.
    const Worst worst = compare_poses(file, {0.25, 0.999, 1.0, 1.6, 2.5});
    CHECK(worst.position <= 1e-5f);
    CHECK(worst.normal <= 1e-5f);
    CHECK(worst.tangent <= 1e-5f);
    MESSAGE("tube, GPU against host: position ", worst.position, ", normal ", worst.normal, ", tangent ",
            worst.tangent);
}

TEST_CASE("gpu pose: a pose of the nodes says whether the GPU has vertices to pose again") {
    PosableScene posable(deforming_box());
    vplkit::scene::VertexPoseFrame frame;
    CHECK(posable.pose_nodes(1.0, frame).vertices);
    CHECK(frame.matrices.size() == posable.vertex_pose_rest().matrix_count);
    CHECK(frame.morph_weights.size() == posable.vertex_pose_rest().weight_count);
    CHECK_FALSE(posable.pose_nodes(1.0, frame).vertices);
    CHECK(posable.pose_nodes(1.5, frame).vertices);
    // The scene's vertices stay as loaded (the GPU writes them); a bad time is the host pose's error.
    const PosableScene loaded(deforming_box());
    for (size_t v = 0; v < loaded.scene().vertices.size(); ++v) {
        CHECK(posable.scene().vertices[v].position == loaded.scene().vertices[v].position);
    }
    CHECK_THROWS_AS(posable.pose_nodes(std::nan(""), frame), vplkit::Error);
}

TEST_CASE("gpu pose: a moving primitive whose normals come from its posed triangles is refused by name") {
    // animated_scene's quad has normals; without them the loader makes flat ones per pose.
    scene_test::GltfBuilder b;
    b.roots.push_back(b.node("{\"mesh\":" + std::to_string(b.mesh("[" + scene_test::unit_quad(b, false) + "]")) + "}"));
    gltf_features::add_animations(b, {{"slide", {{0, "translation", "LINEAR", {0.0f, 1.0f}, {0, 0, 0, 1, 0, 0}}}}});
    scene_test::TempDir dir("gpu_pose_flat");
    PosableScene posable(b.write(dir.path(), "flat", true));
    CHECK(posable.vertex_pose_refusal() ==
          "node 0 mesh 0 primitive 0 moves, but its flat normals are made from the "
          "posed triangles");
    vplkit::scene::VertexPoseFrame frame;
    CHECK_THROWS_WITH_AS(posable.pose_nodes(0.5, frame), doctest::Contains("the GPU cannot pose"), vplkit::Error);
}

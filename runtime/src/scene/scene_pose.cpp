// PosableScene: the loaded model kept, posed again by the loader's own flattening
// (gltf_instances), the triangles checked to be the same, and only the moving parts copied.

#include "vplkit/scene_pose.hpp"

#include "scene/gltf_animation.hpp"
#include "scene/gltf_file.hpp"
#include "scene/gltf_instances.hpp"
#include "scene/gltf_vertex_pose.hpp"
#include "vplkit/error.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace vplkit::scene {

namespace {

// The node properties an animation writes (gltf_animation's pose_node), as the file gives them.
struct RestNode {
    std::vector<double> translation, rotation, scale, weights;
};

bool same_light(const Light& a, const Light& b) {
    return a.position == b.position && a.direction == b.direction && a.color == b.color && a.intensity == b.intensity &&
           a.range == b.range && a.inner_cone_angle == b.inner_cone_angle && a.outer_cone_angle == b.outer_cone_angle;
}

bool same_camera(const Camera& a, const Camera& b) {
    return a.position == b.position && a.forward == b.forward && a.up == b.up && a.yfov == b.yfov && a.xmag == b.xmag &&
           a.ymag == b.ymag;
}

// Of every triangle's vertices, as the loader computes them.
void update_bounds(Scene& scene) {
    scene.bounds.min = glm::vec3(std::numeric_limits<float>::max());
    scene.bounds.max = glm::vec3(std::numeric_limits<float>::lowest());
    for (uint32_t i : scene.indices) {
        scene.bounds.min = glm::min(scene.bounds.min, scene.vertices[i].position);
        scene.bounds.max = glm::max(scene.bounds.max, scene.vertices[i].position);
    }
}

bool same_vertex_pose(const Vertex& a, const Vertex& b) {
    return a.position == b.position && a.normal == b.normal && a.tangent == b.tangent;
}

}  // namespace

struct PosableScene::State {
    std::filesystem::path path;
    LoadOptions options;
    tinygltf::Model model;
    std::vector<RestNode> rest;
    detail::DecodedMeshes decoded;
    std::vector<Material> file_materials;  // as loaded (the caller may change the scene's)
    uint32_t default_material = 0;
    size_t file_lights = 0;
    size_t file_cameras = 0;
    Scene scene;
    // The GPU pose's inputs, made on first use, and the frame pose_nodes gave last.
    std::optional<detail::VertexPoseSetup> vertex_pose;
    VertexPoseFrame vertex_pose_frame;
};

PosableScene::PosableScene(const std::filesystem::path& path, const LoadOptions& options)
    : state_(std::make_unique<State>()) {
    State& s = *state_;
    s.path = path;
    s.options = options;
    detail::CapturedImages captured;
    std::string warn;
    s.model = detail::read_gltf_file(path, captured, warn);
    for (const tinygltf::Node& node : s.model.nodes) {
        s.rest.push_back({node.translation, node.rotation, node.scale, node.weights});
    }
    s.scene = detail::scene_from_model(path, s.model, captured, warn, options, s.decoded);
    s.file_materials = s.scene.materials;
    s.default_material = uint32_t(s.model.materials.size());
    for (const Light& light : s.scene.lights) s.file_lights += light.origin == LightOrigin::file ? 1 : 0;
    for (const Camera& camera : s.scene.cameras) s.file_cameras += camera.origin == CameraOrigin::file ? 1 : 0;
}

PosableScene::~PosableScene() = default;
PosableScene::PosableScene(PosableScene&&) noexcept = default;
PosableScene& PosableScene::operator=(PosableScene&&) noexcept = default;

Scene& PosableScene::scene() {
    return state_->scene;
}
const Scene& PosableScene::scene() const {
    return state_->scene;
}

namespace {

// The model's nodes at `time` (rest transforms restored, the animations' values written) and
// the scene they flatten to: cameras, lights and, with `primitives`, the posed vertices.
Scene posed_nodes(PosableScene::State& s, const detail::GltfSource& source, double time, bool primitives) {
    if (!std::isfinite(time)) source.fail("the time to pose the scene at is not finite");
    for (size_t n = 0; n < s.rest.size(); ++n) {
        tinygltf::Node& node = s.model.nodes[n];
        node.translation = s.rest[n].translation;
        node.rotation = s.rest[n].rotation;
        node.scale = s.rest[n].scale;
        node.weights = s.rest[n].weights;
    }
    LoadOptions options = s.options;
    options.time = time;
    Scene posed;  // the flattened nodes only: what a pose can change
    posed.animations = detail::pose_animations(source, s.model, options, posed.time, posed.warnings);
    detail::append_node_instances(source, std::span<const Material>(s.file_materials).first(s.default_material),
                                  s.default_material, s.decoded, posed, primitives);
    return posed;
}

// The file's lights and cameras, the time and the animations applied, from `posed` into the scene.
void take_nodes(PosableScene::State& s, const Scene& posed, PoseChange& change) {
    Scene& scene = s.scene;
    // The file's lights, in the order load_gltf put them (first, before any the caller added).
    size_t kept_file_lights = 0;
    for (const Light& light : scene.lights) kept_file_lights += light.origin == LightOrigin::file ? 1 : 0;
    if (kept_file_lights == s.file_lights && posed.lights.size() == s.file_lights) {
        size_t next = 0;
        for (Light& light : scene.lights) {
            if (light.origin != LightOrigin::file) continue;
            const Light& moved = posed.lights[next++];
            if (same_light(light, moved)) continue;
            change.lights = true;
            light.position = moved.position;
            light.direction = moved.direction;
            light.color = moved.color;
            light.intensity = moved.intensity;
            light.range = moved.range;
            light.inner_cone_angle = moved.inner_cone_angle;
            light.outer_cone_angle = moved.outer_cone_angle;
        }
    }
    if (posed.cameras.size() == s.file_cameras) {
        size_t next = 0;
        for (Camera& camera : scene.cameras) {
            if (camera.origin != CameraOrigin::file || next >= posed.cameras.size()) continue;
            const Camera& moved = posed.cameras[next++];
            change.cameras |= !same_camera(camera, moved);
            camera = moved;
        }
    }
    scene.time = posed.time;
    for (size_t a = 0; a < scene.animations.size() && a < posed.animations.size(); ++a) {
        scene.animations[a].applied = posed.animations[a].applied;
    }
}

}  // namespace

PoseChange PosableScene::pose(double time) {
    State& s = *state_;
    const std::string file = s.path.string();
    const detail::GltfSource source{s.model, file};
    const Scene posed = posed_nodes(s, source, time, true);

    Scene& scene = s.scene;
    if (posed.indices != scene.indices || posed.triangle_materials != scene.triangle_materials ||
        posed.vertices.size() != scene.vertices.size()) {
        source.fail("posed at t = " + std::to_string(time) + ", the scene has " +
                    std::to_string(posed.triangle_count()) + " triangles over " +
                    std::to_string(posed.vertices.size()) + " vertices, where it had " +
                    std::to_string(scene.triangle_count()) + " over " + std::to_string(scene.vertices.size()) +
                    (posed.triangle_count() == scene.triangle_count() ? " (some wound the other way)" : "") +
                    ": a pose moves vertices, it does not change triangles; load the file at that time instead");
    }

    PoseChange change;
    for (size_t v = 0; v < scene.vertices.size() && !change.vertices; ++v) {
        change.vertices = !same_vertex_pose(scene.vertices[v], posed.vertices[v]);
    }
    if (change.vertices) {
        for (size_t v = 0; v < scene.vertices.size(); ++v) {
            scene.vertices[v].position = posed.vertices[v].position;
            scene.vertices[v].normal = posed.vertices[v].normal;
            scene.vertices[v].tangent = posed.vertices[v].tangent;
        }
        update_bounds(scene);
    }
    take_nodes(s, posed, change);
    // A later pose_nodes compares its frame with this pose's.
    if (s.vertex_pose && s.vertex_pose->refusal.empty()) {
        s.vertex_pose_frame = detail::vertex_pose_frame(source, *s.vertex_pose);
    }
    return change;
}

const detail::VertexPoseSetup& PosableScene::vertex_pose_setup() const {
    State& s = *state_;
    if (!s.vertex_pose) {
        const std::string file = s.path.string();
        const detail::GltfSource source{s.model, file};
        s.vertex_pose = detail::vertex_pose_setup(source, s.decoded, s.scene);
        // The nodes stand as last posed (or loaded): the scene's vertices are this frame's pose.
        if (s.vertex_pose->refusal.empty()) s.vertex_pose_frame = detail::vertex_pose_frame(source, *s.vertex_pose);
    }
    return *s.vertex_pose;
}

const VertexPoseRest& PosableScene::vertex_pose_rest() const {
    return vertex_pose_setup().rest;
}

const std::string& PosableScene::vertex_pose_refusal() const {
    return vertex_pose_setup().refusal;
}

PoseChange PosableScene::pose_nodes(double time, VertexPoseFrame& frame) {
    State& s = *state_;
    const std::string file = s.path.string();
    const detail::GltfSource source{s.model, file};
    const detail::VertexPoseSetup& setup = vertex_pose_setup();
    if (!setup.refusal.empty()) source.fail("the GPU cannot pose this scene's vertices: " + setup.refusal);
    const Scene posed = posed_nodes(s, source, time, false);
    VertexPoseFrame posed_frame = detail::vertex_pose_frame(source, setup);
    PoseChange change;
    change.vertices = posed_frame != s.vertex_pose_frame;
    s.vertex_pose_frame = posed_frame;
    frame = std::move(posed_frame);
    take_nodes(s, posed, change);
    return change;
}

void PosableScene::take_posed_vertices(std::span<const Vertex> posed) {
    State& s = *state_;
    const std::string file = s.path.string();
    const detail::GltfSource source{s.model, file};
    Scene& scene = s.scene;
    if (posed.size() != scene.vertices.size()) {
        source.fail("a GPU pose gave " + std::to_string(posed.size()) + " vertices, the scene has " +
                    std::to_string(scene.vertices.size()));
    }
    for (size_t v = 0; v < posed.size(); ++v) {
        const glm::vec3 p = posed[v].position;
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            source.fail("posed on the GPU, vertex " + std::to_string(v) + " is not finite");
        }
    }
    for (size_t v = 0; v < posed.size(); ++v) {
        scene.vertices[v].position = posed[v].position;
        scene.vertices[v].normal = posed[v].normal;
        scene.vertices[v].tangent = posed[v].tangent;
    }
    update_bounds(scene);
}

}  // namespace vplkit::scene

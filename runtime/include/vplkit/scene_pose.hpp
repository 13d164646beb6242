#pragma once
// A glTF scene kept posable: the file is read once and then posed at any time without reading it
// again (no file access, no JSON parse, no image decoding). The parsed model and each mesh's
// decoded primitives are kept; a pose restores the nodes' rest transforms, writes the animations'
// values at t into them and flattens the nodes again (morphs, skins, node transforms) through the
// loader's own code, so the scene posed at t is exactly load_gltf's at t.
//
//   vplkit::scene::PosableScene posable("walk.gltf");
//   vplkit::Renderer renderer(context, posable.scene());
//   for (frame ...) renderer.update_pose(posable.pose(frame / fps)), renderer.render(...);

#include "vplkit/scene.hpp"
#include "vplkit/scene_vertex_pose.hpp"

#include <filesystem>
#include <memory>
#include <span>
#include <string>

namespace vplkit::scene {

namespace detail {
struct VertexPoseSetup;
}

// What a pose changed, so that a renderer updates only that (Renderer::update_pose).
struct PoseChange {
    bool vertices = false;  // some vertex position, normal or tangent moved (the triangles are the same)
    bool lights = false;    // some light of the file moved, turned, or changed colour or intensity
    bool cameras = false;   // some camera of the file moved or turned
    bool any() const { return vertices || lights || cameras; }
};

class PosableScene {
public:
    // load_gltf(path, options), keeping what posing again needs. Throws what load_gltf throws.
    explicit PosableScene(const std::filesystem::path& path, const LoadOptions& options = {});
    ~PosableScene();
    PosableScene(PosableScene&&) noexcept;
    PosableScene& operator=(PosableScene&&) noexcept;

    // The scene as last posed. It stays at the same address for this object's life (a Renderer
    // may hold it); the caller may change its materials and add lights, as after load_gltf.
    Scene& scene();
    const Scene& scene() const;

    // Poses the scene at `time` (seconds; the animation chosen at load, else all of them, each
    // channel clamped to its keys as LoadOptions::time says): vertices, the file's lights and
    // cameras, bounds and Scene::time. Materials, textures, images and lights the caller added
    // are kept; when the caller removed or replaced the file's lights, lights are left as they are.
    // Throws Error for a non-finite time, and when the pose changes the triangles themselves (a
    // triangle that turns degenerate or back, a node transform that starts or stops mirroring):
    // load the file at that time instead. On a throw the scene is unchanged.
    PoseChange pose(double time);

    // The moving vertices posed on the GPU instead (vplkit/scene_vertex_pose.hpp). Why the GPU
    // pass cannot pose this scene as pose() does (one line naming the instance), else empty.
    const std::string& vertex_pose_refusal() const;
    // What the GPU pose keeps: the moving instances' rest vertices, joints, weights and morph
    // displacements (made on first use).
    const VertexPoseRest& vertex_pose_rest() const;
    // pose(time) without the vertices: the file's lights and cameras, Scene::time and the
    // animations applied as pose() sets them, and `frame` the moving instances' matrices and
    // morph weights at `time`. PoseChange::vertices says whether those changed since the last
    // pose or pose_nodes (the first: since the pose the scene had when the GPU pose was first
    // asked for). Scene::vertices and Scene::bounds stay as they were: the GPU pass writes the
    // vertices (take_posed_vertices brings them back).
    // Throws Error for a non-finite time and when vertex_pose_refusal() is not empty.
    PoseChange pose_nodes(double time, VertexPoseFrame& frame);
    // The vertices a GPU pose wrote (as many as the scene has, in its order) taken into the scene:
    // positions, normals and tangents, and the bounds. Throws Error naming the first vertex whose
    // position is not finite, or for another count; on a throw the scene is unchanged.
    void take_posed_vertices(std::span<const Vertex> posed);

    struct State;  // the implementation's

private:
    const detail::VertexPoseSetup& vertex_pose_setup() const;

    std::unique_ptr<State> state_;
};

}  // namespace vplkit::scene

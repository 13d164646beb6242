#pragma once
// The scene model a renderer consumes directly, loaded from a glTF 2.0 file (.gltf or .glb):
// world-space triangles flattened from every instance of every triangle primitive (node
// transforms applied, one copy per node that uses a mesh), PBR metallic-roughness materials,
// RGBA8 images, KHR_lights_punctual lights and cameras. Units are the file's.
//
// load_gltf() either returns a complete Scene or throws one vplkit::Error whose message starts
// with the file's path and names the problem; nothing partial is ever returned.

#include "vplkit/scene_lights.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace vplkit::scene {

// One vertex: 72 bytes, no padding, so the vector uploads as a vertex buffer or as a
// scalar-layout storage buffer as it is.
struct Vertex {
    glm::vec3 position{0.0f};  // world space
    glm::vec3 normal{0.0f};    // world space, unit length
    // World space: xyz unit length and orthogonal to the normal, pointing where u grows; w = +1
    // or -1, the bitangent is w * cross(normal, tangent.xyz) (the glTF convention) and points
    // where v shrinks (up in the image, as normal maps store green). All zero when the file gives
    // no tangents and the primitive's material has no normal texture (nothing needs one then).
    glm::vec4 tangent{0.0f};
    glm::vec2 uv0{0.0f};  // TEXCOORD_0 ((0, 0) when the primitive has none)
    glm::vec2 uv1{0.0f};  // TEXCOORD_1 ((0, 0) when the primitive has none)
    // COLOR_0, linear RGBA in [0, 1] (RGB files get a = 1; white when the primitive has none): it
    // multiplies the material's base colour (glTF 2.0 3.9.2).
    glm::vec4 color{1.0f};
};
static_assert(sizeof(Vertex) == 72, "Vertex is uploaded as is: no padding");

enum class AlphaMode : uint32_t { opaque, mask, blend };
enum class Wrap : uint32_t { repeat, clamp_to_edge, mirrored_repeat };
enum class Filter : uint32_t { nearest, linear };
enum class MipmapMode : uint32_t { none, nearest, linear };

// A glTF sampler; the file's "undefined" filters become linear with linear mipmaps.
struct Sampler {
    Wrap wrap_s = Wrap::repeat;
    Wrap wrap_t = Wrap::repeat;
    Filter mag_filter = Filter::linear;
    Filter min_filter = Filter::linear;
    MipmapMode mipmap_mode = MipmapMode::linear;
};

// A decoded image, kept once however many textures use it.
struct Image {
    std::string name;  // the file's uri, else its name, else "image N"
    uint32_t width = 0;
    uint32_t height = 0;
    // width * height * 4 bytes, rows top to bottom, 8 bits a channel (16-bit files are rounded;
    // grey and RGB files get A = 255).
    std::vector<uint8_t> rgba;
    // How the materials use it: colour data (base colour, emissive: sample through an sRGB view)
    // and/or plain data (metallic-roughness, normal map: sample through a UNORM view). An image
    // used both ways has both set; the renderer then needs both views.
    bool srgb = false;
    bool linear = false;
};

struct Texture {
    uint32_t image = 0;  // index into Scene::images
    Sampler sampler;
};

inline constexpr int32_t kNoTexture = -1;

// How one texture reference maps a vertex's texture coordinates to the texture: its set
// (textureInfo.texCoord, or KHR_texture_transform's override) and KHR_texture_transform's
// uv' = T(offset) R(rotation) S(scale) uv, with R = [cos sin; -sin cos] as the extension writes
// it (a positive rotation turns the UVs counter-clockwise in the image, whose v points down).
struct UvTransform {
    uint32_t tex_coord = 0;  // 0: Vertex::uv0, 1: Vertex::uv1
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;  // radians
    glm::vec2 scale{1.0f};

    // Rows of the 2x3 matrix: u' = dot(u_row, (u, v, 1)), v' = dot(v_row, (u, v, 1)).
    glm::vec3 u_row() const;
    glm::vec3 v_row() const;
    glm::vec2 apply(glm::vec2 uv) const;
    bool identity() const { return offset == glm::vec2(0.0f) && rotation == 0.0f && scale == glm::vec2(1.0f); }
};

// glTF 2.0 metallic-roughness material; texture members index Scene::textures (kNoTexture: none),
// each read through its UvTransform. The occlusion texture is not kept (VPLs compute the
// indirect light it would approximate).
struct Material {
    std::string name;
    glm::vec4 base_color_factor{1.0f};        // linear RGBA
    int32_t base_color_texture = kNoTexture;  // sRGB; multiplies the factor
    float metallic_factor = 1.0f;
    float roughness_factor = 1.0f;
    int32_t metallic_roughness_texture = kNoTexture;  // linear; G = roughness, B = metallic
    int32_t normal_texture = kNoTexture;              // linear, tangent space
    float normal_scale = 1.0f;
    glm::vec3 emissive_factor{0.0f};        // linear RGB
    float emissive_strength = 1.0f;         // KHR_materials_emissive_strength
    int32_t emissive_texture = kNoTexture;  // sRGB; multiplies the factor
    UvTransform base_color_uv;
    UvTransform metallic_roughness_uv;
    UvTransform normal_uv;
    UvTransform emissive_uv;
    AlphaMode alpha_mode = AlphaMode::opaque;
    float alpha_cutoff = 0.5f;  // AlphaMode::mask only
    bool double_sided = false;

    // Emitted radiance scale: emissive factor times strength (times the texture, where there is one).
    glm::vec3 emission() const { return emissive_factor * emissive_strength; }
    bool emits() const {
        const glm::vec3 e = emission();
        return e.x > 0.0f || e.y > 0.0f || e.z > 0.0f;
    }
};

enum class CameraOrigin : uint32_t { file, generated, setup };
enum class Projection : uint32_t { perspective, orthographic };

// A perspective or orthographic camera. position/forward/up are the node's world transform with
// any scale removed (glTF cameras look down their local -Z with +Y up).
struct Camera {
    std::string name;
    CameraOrigin origin = CameraOrigin::file;
    Projection projection = Projection::perspective;
    glm::vec3 position{0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f};  // unit
    glm::vec3 up{0.0f, 1.0f, 0.0f};        // unit, orthogonal to forward
    float yfov = 0.0f;                     // perspective: vertical field of view, radians
    float aspect = 0.0f;                   // perspective: width / height; 0 when the file leaves it to the image
    // Orthographic: half the view's width and height in world units (glTF xmag, ymag). The image's
    // aspect ratio decides the width, as it does a perspective camera's (pixels stay square):
    // xmag is kept for reference.
    float xmag = 0.0f;
    float ymag = 0.0f;
    float znear = 0.0f;  // orthographic: may be 0
    float zfar = 0.0f;   // perspective: 0 = infinite (glTF); orthographic: > znear

    // Rigid transform: columns right, up, -forward, position.
    glm::mat4 world_from_camera() const;
    // Its inverse (a right-handed look-at view matrix).
    glm::mat4 view() const;
};

// A camera at `position` looking at `target` (up is made orthogonal to the view direction).
// Throws vplkit::Error when target == position, up is parallel to the view direction, or yfov is
// not in (0, pi).
Camera look_at(glm::vec3 position, glm::vec3 target, glm::vec3 up, float yfov);

struct Bounds {
    glm::vec3 min{0.0f};
    glm::vec3 max{0.0f};
    glm::vec3 center() const { return (min + max) * 0.5f; }
    glm::vec3 extent() const { return max - min; }
};

enum class NormalSource : uint32_t {
    file,           // the primitive's NORMAL, transformed with the inverse transpose
    generated_flat  // no NORMAL: one face normal per triangle (its vertices are not shared),
                    // as the glTF 2.0 specification asks of a client
};
enum class TangentSource : uint32_t {
    none,      // no TANGENT and no normal texture: tangents are zero
    file,      // the primitive's TANGENT, transformed
    generated  // per triangle from the UVs, area-weighted average per vertex, Gram-Schmidt
               // against the normal, handedness in w (see generate_tangents in the loader)
};

// One node's instance of one glTF primitive: a contiguous range of vertices and triangles.
struct PrimitiveInstance {
    uint32_t node = 0;
    uint32_t mesh = 0;
    uint32_t primitive = 0;  // index within the mesh
    uint32_t material = 0;   // index into Scene::materials
    uint32_t first_vertex = 0;
    uint32_t vertex_count = 0;
    uint32_t first_triangle = 0;
    uint32_t triangle_count = 0;
    NormalSource normals = NormalSource::file;
    TangentSource tangents = TangentSource::none;
    bool mirrored = false;  // negative-determinant transform: winding was reversed to stay CCW
};

// What the loader skipped or repaired instead of failing.
struct LoadWarnings {
    uint32_t skipped_primitives = 0;  // mode other than TRIANGLES (points, lines, strips, fans)
    // Zero area in world space (a repeated corner, collinear corners, or a height below float
    // resolution of the longest edge: under FLT_EPSILON times its length): dropped.
    uint32_t degenerate_triangles = 0;
    uint32_t repaired_normals = 0;      // zero-length NORMAL: replaced by the adjacent faces' normal
    uint32_t untangented_vertices = 0;  // generated tangent undefined (no UVs or degenerate UVs):
                                        // an arbitrary unit vector orthogonal to the normal, w = +1
    std::vector<std::string> messages;  // each other thing ignored or approximated, one line each
};

// What a user is told about `warnings`: one line per thing the loader skipped or approximated
// (the counters as sentences, then the messages), each line once, in the order first met. A
// scene that renders exactly as its file states has none. Zero-area triangles are not among
// them (nothing could draw them: see degenerate_triangles_note).
std::vector<std::string> warning_lines(const LoadWarnings& warnings);
// The dropped zero-area triangles as a line (empty when there were none): they change no image.
std::string degenerate_triangles_note(const LoadWarnings& warnings);

// One glTF animation of the file (glTF 2.0 3.11), for a sequence to loop or clamp over.
struct Animation {
    std::string name;      // the file's ("" when unnamed)
    double start = 0.0;    // its earliest key, seconds
    double end = 0.0;      // its latest key, seconds (end - start: its duration)
    bool applied = false;  // posed into this scene (see LoadOptions::time and ::animation)
};

struct Scene {
    std::filesystem::path source;  // the file it was loaded from

    std::vector<Vertex> vertices;
    // One random integer per vertex (the FLC paper sec. 3), from the vertex's identity in the file
    // (node, mesh, primitive, vertex index: see vertex_random_value), never from its position, so
    // a triangle's random number (the xor of its three) stays the same when its node moves, turns,
    // scales or is skinned. Forward light cuts read it; parallel to `vertices`.
    std::vector<uint32_t> vertex_random;
    std::vector<uint32_t> indices;             // 3 per triangle; counter-clockwise = front
    std::vector<uint32_t> triangle_materials;  // one per triangle, index into materials
    std::vector<uint32_t> emissive_triangles;  // the triangles whose material emits, ascending
    std::vector<PrimitiveInstance> primitives;

    // The file's materials in the file's order; a last one named "default" (glTF's default
    // material: white, metallic 1, roughness 1) when some primitive has none.
    std::vector<Material> materials;
    std::vector<Texture> textures;  // only those the materials use, in order of first use
    std::vector<Image> images;      // only those the textures use, in order of first use

    std::vector<Light> lights;
    // The scene's cameras (perspective and orthographic) in node order (depth first from the scene's root nodes);
    // when the file has none, one generated camera (see load_gltf).
    std::vector<Camera> cameras;
    uint32_t active_camera = 0;

    Bounds bounds;  // of every triangle's vertices
    LoadWarnings warnings;

    // The file's animations in the file's order, and the time the scene is posed at (unset: the
    // rest pose, every animation ignored).
    std::vector<Animation> animations;
    std::optional<double> time;

    size_t triangle_count() const { return indices.size() / 3; }
    const Camera& camera() const { return cameras.at(active_camera); }
};

struct LoadOptions {
    // The camera to make active (index into the file's cameras, as Scene::cameras orders them).
    // A file without that camera is an error. Unset: camera 0, or the generated one.
    std::optional<uint32_t> camera;
    // The time, in seconds, to pose the scene at: nodes (hence meshes, skins' joints, lights and
    // cameras) and morph weights take the animations' values at it (glTF 2.0 3.11, Appendix C).
    // Each channel is clamped to its own keys: before its first key it holds the first key's
    // value, after its last the last's (no wrapping: a sequence loops or clamps by choosing the
    // time from Scene::animations). Unset: the rest pose, the animations ignored (warned), unless
    // `animation` is set, which then poses the scene at that animation's start.
    std::optional<double> time;
    // The animation to play: a name of one of the file's animations, else its index in the file
    // (decimal). Unset: every animation of the file at `time`; where two of them animate the same
    // node property the later in the file wins (warned). A name or index the file lacks is an error.
    std::optional<std::string> animation;
};

// Loads `path` (.gltf with external or embedded buffers and images, or .glb) and the scene it
// names as default (else scene 0; else every root node). When the file has no camera,
// one is generated to frame the bounds: looking down -Z from the +Z side (glTF's front), at the
// centre of the bounds' bounding sphere, vertical field of view 45 degrees, far enough that the
// whole sphere is in view for any aspect ratio >= 1.
//
// Errors (vplkit::Error, message "<path>: <problem>"): file missing or unreadable, malformed JSON,
// missing or truncated buffer, missing or undecodable image a material uses, an accessor or
// bufferView outside its buffer, an index outside its vertices, NaN/Inf in a vertex attribute or a
// transform, no triangle left, an extension in extensionsRequired that vplkit does not support,
// options.camera out of range, options.animation not in the file, a malformed animation (a
// sampler whose times are not strictly increasing, key and value counts that disagree, a channel
// naming a node the file lacks or one that has a matrix, a path animated twice in one animation;
// every animation is checked, applied or not).
Scene load_gltf(const std::filesystem::path& path, const LoadOptions& options = {});

// The random integer load_gltf gives vertex `vertex` (the file's index within its primitive) of
// `primitive` of `mesh` instanced by `node`: chained PCG hashes, uniform over 32 bits.
uint32_t vertex_random_value(uint32_t node, uint32_t mesh, uint32_t primitive, uint32_t vertex);

// The vertices of every triangle in order, 3 per triangle (for BVH builders and tests).
std::vector<glm::vec3> triangle_positions(const Scene& scene);

// Makes every material a pure Lambertian reflector of its base colour (metallic 0, no
// metallic-roughness texture, roughness kLambertianRoughness, which brdf.glsl evaluates as
// base colour / pi): for comparisons with references that render diffuse-only, such as
// ../shared/reference (`vplkit render --brdf lambert`).
inline constexpr float kLambertianRoughness = -1.0f;
void use_lambertian_materials(Scene& scene);

// The generated camera load_gltf uses when a file has none.
Camera framing_camera(const Bounds& bounds);

}  // namespace vplkit::scene

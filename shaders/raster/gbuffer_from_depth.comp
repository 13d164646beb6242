#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
// The G-buffer adapter: the kit's G-buffer (vplkit/gbuffer.glsl) from what a renderer already
// has: a depth image with its inverse view-projection, a normal image in one of several
// encodings, an albedo image, optionally a roughness/metallic image. Host side and every option:
// stages/include/vplkit/stages/gbuffer_adapter.hpp.
//
// The inputs are sampled images read with texelFetch (no sampler, no filtering): the format's
// conversion (UNORM, SNORM, sRGB, float, any depth format) is the image view's, so one shader
// reads them all. The encodings are specialization constants (lavapipe runs both sides of a
// runtime branch).

layout(local_size_x = 8, local_size_y = 8) in;

// How the normal image holds a unit vector (GbufferNormalEncoding in gbuffer_adapter.hpp).
const uint kNormalXyz = 0u;             // xyz as is (float or SNORM formats)
const uint kNormalXyzUnorm = 1u;        // xyz = n * 0.5 + 0.5 (RGB10A2, RGBA8 UNORM)
const uint kNormalOctahedral = 2u;      // xy = octahedral in [-1, 1] (RG16 SNORM, RG16F, RG8 SNORM)
const uint kNormalOctahedralUnorm = 3u; // xy = octahedral * 0.5 + 0.5 (RG16 UNORM, RG8 UNORM)

layout(constant_id = 0) const uint kNormalEncoding = kNormalXyz;
layout(constant_id = 1) const bool kNormalInViewSpace = false;
layout(constant_id = 2) const bool kReversedDepth = false;
layout(constant_id = 3) const bool kMaterialImage = false;  // roughness/metallic from an image, else constants
layout(constant_id = 4) const uint kRoughnessChannel = 1u;  // glTF's metallicRoughness texture: G
layout(constant_id = 5) const uint kMetallicChannel = 2u;   // ... and B

layout(set = 0, binding = 0) uniform texture2D depth_image;
layout(set = 0, binding = 1) uniform texture2D normal_image;
layout(set = 0, binding = 2) uniform texture2D albedo_image;
layout(set = 0, binding = 3) uniform texture2D material_image;  // the albedo image again when unused
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D out_position;
layout(set = 0, binding = 5, rgba32f) uniform writeonly image2D out_normal;
layout(set = 0, binding = 6, rgba32f) uniform writeonly image2D out_geometric_normal;
layout(set = 0, binding = 7, rgba16f) uniform writeonly image2D out_albedo;

layout(push_constant) uniform GbufferFromDepthPush {
    mat4 inverse_view_projection;  // Vulkan clip space (depth as stored) -> world
    vec3 view_to_world_x;          // the rotation from the normals' view space to world (columns)
    float roughness;               // without a material image
    vec3 view_to_world_y;
    float metallic;                // without a material image
    vec3 view_to_world_z;
    float depth_quantum;           // the depth format's absolute step (UNORM: 2^-bits; float: 0)
} push;

// The same pull as gbuffer_shade.frag (its comment says why the stored position moves toward
// the viewer): at least 2^-16 of the coordinates, and 2 depth ulps with a margin of 2 as a
// distance along the ray (here also 2 steps of a UNORM depth format).
const float kViewerPull = 1.52587890625e-5;
const float kDepthResolution = 2.384185791015625e-7;

float far_depth() { return kReversedDepth ? 0.0 : 1.0; }
float near_depth() { return kReversedDepth ? 1.0 : 0.0; }

vec2 pixel_ndc(ivec2 pixel, ivec2 size) { return (vec2(pixel) + 0.5) / vec2(size) * 2.0 - 1.0; }

vec3 unproject(vec2 ndc, float depth) {
    vec4 h = push.inverse_view_projection * vec4(ndc, depth, 1.0);
    return h.xyz / h.w;
}

bool is_background(float depth) { return kReversedDepth ? !(depth > 0.0) : !(depth < 1.0); }

// Octahedral unit vector decoding (Cigolle et al. 2014, "A Survey of Efficient Representations
// for Independent Unit Vectors", JCGT 3(2), listing 1).
vec3 octahedral_decode(vec2 e) {
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) {
        vec2 sign_not_zero = vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
        n.xy = (1.0 - abs(n.yx)) * sign_not_zero;
    }
    return n;
}

vec3 decode_normal(vec4 texel) {
    vec3 n;
    if (kNormalEncoding == kNormalXyz) {
        n = texel.xyz;
    } else if (kNormalEncoding == kNormalXyzUnorm) {
        n = texel.xyz * 2.0 - 1.0;
    } else if (kNormalEncoding == kNormalOctahedral) {
        n = octahedral_decode(texel.xy);
    } else {
        n = octahedral_decode(texel.xy * 2.0 - 1.0);
    }
    if (kNormalInViewSpace) {
        n = push.view_to_world_x * n.x + push.view_to_world_y * n.y + push.view_to_world_z * n.z;
    }
    float length2 = dot(n, n);
    return length2 > 0.0 ? n * inversesqrt(length2) : vec3(0.0);
}

// The neighbour at `offset` on one axis and its opposite: the one whose depth differs less from
// the centre's (the other may lie across an edge), as a tangent pointing along +offset. False when
// neither is a surface inside the image.
bool depth_tangent(ivec2 pixel, ivec2 size, float depth, vec3 p, ivec2 offset, out vec3 tangent) {
    ivec2 a = pixel + offset, b = pixel - offset;
    bool a_ok = all(greaterThanEqual(a, ivec2(0))) && all(lessThan(a, size));
    bool b_ok = all(greaterThanEqual(b, ivec2(0))) && all(lessThan(b, size));
    float da = a_ok ? texelFetch(depth_image, a, 0).r : far_depth();
    float db = b_ok ? texelFetch(depth_image, b, 0).r : far_depth();
    a_ok = a_ok && !is_background(da);
    b_ok = b_ok && !is_background(db);
    if (!a_ok && !b_ok) {
        return false;
    }
    bool use_a = a_ok && (!b_ok || abs(da - depth) <= abs(db - depth));
    tangent = use_a ? unproject(pixel_ndc(a, size), da) - p : p - unproject(pixel_ndc(b, size), db);
    return true;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(out_position);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    float depth = texelFetch(depth_image, pixel, 0).r;
    if (is_background(depth)) {
        // As the raster pass clears: coverage 0 and every other channel 0.
        imageStore(out_position, pixel, vec4(0.0));
        imageStore(out_normal, pixel, vec4(0.0));
        imageStore(out_geometric_normal, pixel, vec4(0.0));
        imageStore(out_albedo, pixel, vec4(0.0));
        return;
    }
    vec2 ndc = pixel_ndc(pixel, size);
    vec4 h = push.inverse_view_projection * vec4(ndc, depth, 1.0);
    vec3 p = h.xyz / h.w;
    // Toward the viewer along the pixel's ray: to the point on the near plane (perspective and
    // orthographic alike).
    vec3 to_viewer = unproject(ndc, near_depth()) - p;
    float viewer_distance = length(to_viewer);
    vec3 u = viewer_distance > 0.0 ? to_viewer / viewer_distance : vec3(0.0);

    vec3 g;
    vec3 tx, ty;
    bool have_x = depth_tangent(pixel, size, depth, p, ivec2(1, 0), tx);
    bool have_y = depth_tangent(pixel, size, depth, p, ivec2(0, 1), ty);
    vec3 n = decode_normal(texelFetch(normal_image, pixel, 0));
    vec3 c = have_x && have_y ? cross(tx, ty) : vec3(0.0);
    float c_length2 = dot(c, c);
    if (c_length2 > 0.0) {
        g = c * inversesqrt(c_length2);
        if (dot(g, u) < 0.0) {
            g = -g;
        }
    } else {
        g = n;  // an isolated pixel: no plane through its neighbours
    }
    // The shading normal to the viewer's side where it faces away from both the viewer and the
    // geometric normal (a back face's normal). Not on g's side alone: a normal map may tilt it
    // away from the viewer, and at an edge g from depth can be far off.
    if (dot(n, g) < 0.0 && dot(n, u) < 0.0) {
        n = -n;
    }

    // The pull of gbuffer_shade.frag: d position / d depth along the ray, from the derivative of
    // the homogeneous unprojection (column 2 of the inverse is d h / d depth).
    vec4 dh = push.inverse_view_projection[2];
    vec3 dp_ddepth = (dh.xyz * h.w - h.xyz * dh.w) / (h.w * h.w);
    vec3 m = abs(p);
    float pull = kViewerPull * max(m.x, max(m.y, m.z));
    pull = max(pull, (kDepthResolution * abs(depth) + 2.0 * push.depth_quantum) * length(dp_ddepth));
    vec3 position = p + u * min(pull, 0.5 * viewer_distance);

    float roughness = push.roughness;
    float metallic = push.metallic;
    if (kMaterialImage) {
        vec4 material = texelFetch(material_image, pixel, 0);
        roughness = material[kRoughnessChannel];
        metallic = material[kMetallicChannel];
    }
    imageStore(out_position, pixel, vec4(position, 1.0));
    imageStore(out_normal, pixel, vec4(n, roughness));
    imageStore(out_geometric_normal, pixel, vec4(g, metallic));
    imageStore(out_albedo, pixel, vec4(texelFetch(albedo_image, pixel, 0).rgb, 1.0));
}

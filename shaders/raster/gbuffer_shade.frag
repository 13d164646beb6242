#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer pass, fragment stage: evaluates the draw's material and writes the G-buffer images
// as shaders/include/vplkit/gbuffer.glsl defines them (position w = 1 and albedo a = 1 mark a
// drawn surface; the host clears position, normals, albedo and emission to 0, depth to 1).

#define VPLKIT_SCENE_MATERIALS_BINDING 2
#define VPLKIT_SCENE_TEXTURES_BINDING 3
#include "vplkit/raster_material.glsl"

// gbuffer_raster.vert's block (one push range for both stages); the addresses are its alone.
layout(push_constant) uniform GbufferPush {
    mat4 view_projection;
    vec3 viewer_position;
    uint material;
    uint has_motion;
    uvec2 scene_vertex_address;
    uvec2 scene_index_address;
    uint scene_vertex_count;
    uint scene_index_count;
    uvec2 previous_vertex_address;
} push;

layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;
layout(location = 2) in vec4 world_tangent;
layout(location = 3) in vec2 uv0;
layout(location = 4) flat in vec3 face_normal;
layout(location = 5) in vec4 vertex_color;
layout(location = 6) in vec2 uv1;
layout(location = 7) flat in float coordinate_magnitude;
layout(location = 8) in vec3 motion;

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_geometric_normal;
layout(location = 3) out vec4 out_albedo;
layout(location = 4) out vec4 out_emission;
layout(location = 5) out vec4 out_motion;

// 2^-16: the least distance the stored position moves toward the viewer, relative to the
// magnitude of the coordinates (the same 128 to 256 float ulps as bvh.glsl's kBvhOriginOffset).
const float kViewerPull = 1.52587890625e-5;
// 2^-22: 2 ulps of a D32 depth in [0.5, 1): the depth test's resolution, with a margin of 2.
const float kDepthResolution = 2.384185791015625e-7;

// The position that screen-space stages start rays from (shadow rays to lights and VPLs): the
// interpolated point moved toward the viewer, into the space the camera ray crossed to reach it,
// which holds no surface. At a concave edge (a wall meeting the ceiling, a block standing on
// the floor) the point can lie on or behind the other surface:
// - a pixel centre's ray can meet both surfaces at once (in the default Cornell box whole
//   diagonals of pixel centres do); the interpolated point is then within rounding of the other
//   surface's plane, on either side;
// - where the two depths differ by less than the depth test resolves, the surface behind can
//   win (a floor pixel just inside a block's face at 1024 x 1024).
// An offset along its own normal (bvh.glsl's offset_ray_origin) leaves such a point there, and
// a shadow ray into the room met the other surface at t ~ 0: isolated black pixels along the
// edges. Moved toward the viewer past both errors, the point is in front of every surface there
// (those the viewer sees face it). The distance: the larger of 2^-16 of the coordinates (of the
// triangle's corners or the point: interpolation rounds relative to them) and 2 depth ulps
// converted to distance along the ray (d depth / dt from the projection); at most half the way
// to the viewer. Shading moves by the same amount: less than the depth buffer can tell apart.
vec3 position_toward_viewer(vec3 p) {
    vec3 to_viewer = push.viewer_position - p;
    float d = length(to_viewer);
    if (!(d > 0.0)) {
        return p;
    }
    vec3 u = to_viewer / d;
    vec3 m = abs(p);
    float pull = kViewerPull * max(coordinate_magnitude, max(m.x, max(m.y, m.z)));
    // Clip-space depth z / w along the ray p + t u: its rate of change at t = 0.
    vec4 clip = push.view_projection * vec4(p, 1.0);
    vec4 clip_rate = push.view_projection * vec4(u, 0.0);
    float depth_rate = abs(clip_rate.z * clip.w - clip.z * clip_rate.w) / (clip.w * clip.w);
    if (depth_rate > 0.0) {
        pull = max(pull, kDepthResolution * abs(clip.z / clip.w) / depth_rate);
    }
    return p + u * min(pull, 0.5 * d);
}

void main() {
    RasterSurface s = raster_surface(scene_materials.items[push.material], vertex_color, world_normal, world_tangent, uv0, uv1, face_normal,
                                     push.viewer_position - world_position);
    out_position = vec4(position_toward_viewer(world_position), 1.0);
    out_normal = vec4(s.normal, s.roughness);
    out_geometric_normal = vec4(s.geometric_normal, s.metallic);
    out_albedo = vec4(s.albedo, 1.0);
    out_emission = vec4(s.emission, 0.0);
    out_motion = vec4(motion, 0.0);
}

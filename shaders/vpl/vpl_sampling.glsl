#ifndef VPLKIT_VPL_SAMPLING_GLSL
#define VPLKIT_VPL_SAMPLING_GLSL

// The warps the light-path tracer draws its directions and points with, each beside its pdf
// (pbrt-v4, sampling.h, is the model: Sample* / *PDF pairs). u is uniform in [0, 1)^2.

const float kSamplingPi = 3.14159265358979323846;

// Duff et al., "Building an Orthonormal Basis, Revisited" (JCGT 6(1), 2017), listing 3: a frame
// around unit n without the singularity of cross products with a fixed axis.
void orthonormal_basis(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

vec3 frame_to_world(vec3 local, vec3 n) {
    vec3 t, b;
    orthonormal_basis(n, t, b);
    return local.x * t + local.y * b + local.z * n;
}

// Uniform direction on the unit sphere (pbrt-v4 SampleUniformSphere).
vec3 sample_uniform_sphere(vec2 u) {
    float z = 1.0 - 2.0 * u.x;
    float r = sqrt(max(0.0, 1.0 - z * z));
    float phi = 2.0 * kSamplingPi * u.y;
    return vec3(r * cos(phi), r * sin(phi), z);
}
float uniform_sphere_pdf() {
    return 1.0 / (4.0 * kSamplingPi);
}

// Uniform direction in the cone of directions within acos(cos_max) of +z (pbrt-v4
// SampleUniformCone): cos(theta) uniform in [cos_max, 1].
vec3 sample_uniform_cone(vec2 u, float cos_max) {
    float cos_theta = 1.0 - u.x * (1.0 - cos_max);
    float sin_theta = sqrt(max(0.0, 1.0 - cos_theta * cos_theta));
    float phi = 2.0 * kSamplingPi * u.y;
    return vec3(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
}
float uniform_cone_pdf(float cos_max) {
    return 1.0 / (2.0 * kSamplingPi * (1.0 - cos_max));
}

// Uniform point on the unit disc (polar map: r = sqrt(u.x), area-preserving).
vec2 sample_uniform_disk(vec2 u) {
    float r = sqrt(u.x);
    float phi = 2.0 * kSamplingPi * u.y;
    return vec2(r * cos(phi), r * sin(phi));
}
float uniform_disk_pdf() {
    return 1.0 / kSamplingPi;
}

// Cosine-weighted direction about +z (Malley's method: a uniform disc point lifted to the
// hemisphere), pdf = cos(theta) / pi.
vec3 sample_cosine_hemisphere(vec2 u) {
    vec2 d = sample_uniform_disk(u);
    return vec3(d, sqrt(max(0.0, 1.0 - dot(d, d))));
}
float cosine_hemisphere_pdf(float cos_theta) {
    return max(cos_theta, 0.0) / kSamplingPi;
}

// Uniform point on a triangle as the barycentric weights (b0, b1, b2) (pbrt-v4
// SampleUniformTriangle's square-root map), pdf = 1 / area.
vec3 sample_uniform_triangle(vec2 u) {
    float s = sqrt(u.x);
    float b0 = 1.0 - s;
    float b1 = u.y * s;
    return vec3(b0, b1, 1.0 - b0 - b1);
}
float uniform_triangle_pdf(float area) {
    return 1.0 / area;
}

#endif

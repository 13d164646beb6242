#ifndef VPLKIT_DENOISE_GLSL
#define VPLKIT_DENOISE_GLSL

// What the denoising stages (shaders/denoise/) share: the luminance they measure noise in, the
// albedo rule of demodulation, and the edge weights of the a-trous filter. The CPU reference
// (tests/reference/denoise_reference.cpp) mirrors each in double.

// Rec. 709 luminance of linear RGB.
float denoise_luminance(vec3 c) {
    return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

// Demodulation divides a channel by the albedo only where the albedo is above min_albedo: a
// black channel carries no texture to keep apart, and dividing by ~0 would make a firefly.
// Remodulation applies the same rule, so the pair is the identity (up to rounding).
vec3 denoise_albedo_divisor(vec3 albedo, float min_albedo) {
    return mix(vec3(1.0), albedo, greaterThan(albedo, vec3(min_albedo)));
}

// The edge-stopping weights of SVGF (Schied et al. 2017, eqs. 3-5), with one difference: the
// depth term is the distance of q from p's tangent plane in world units (the G-buffer holds world
// positions, no depth gradients), so pixels of one plane weigh 1 at every step size and a depth
// step weighs exp(-gap / sigma_plane).
float denoise_plane_weight(vec3 p, vec3 n_p, vec3 q, float sigma_plane) {
    return exp(-abs(dot(n_p, q - p)) / sigma_plane);
}

float denoise_normal_weight(vec3 n_p, vec3 n_q, float sigma_normal) {
    return pow(max(dot(n_p, n_q), 0.0), sigma_normal);
}

#endif

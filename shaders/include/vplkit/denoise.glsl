#ifndef VPLKIT_DENOISE_GLSL
#define VPLKIT_DENOISE_GLSL

// What the denoising stages (shaders/denoise/) share: the luminance they measure noise in, the
// albedo rule of demodulation, and the edge weights of the a-trous filter. The CPU reference
// (tests/reference/denoise_reference.cpp) mirrors each in double.

// Rec. 709 luminance of linear RGB.
float denoise_luminance(vec3 c) {
    return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

// Demodulation divides each channel by max(albedo, albedo_floor); remodulation multiplies by the
// same, so the pair is the identity (up to rounding) for any albedo, black channels included.
// Why a floor and not "divide only where the albedo is above a threshold": every filter between
// the two (upsampling, accumulation, a-trous) mixes a pixel's irradiance with its neighbours' and
// the pixel multiplies the mix by ITS divisor. With a threshold, a channel just above it was divided
// (irradiance E) while one below was not (its radiance, ~0), so a pixel below the threshold took its
// neighbours' E times 1: full irradiance in a channel whose albedo is ~0 (green and cyan specks on
// dark-red textures). With a floor, the divisor is continuous in the albedo and never below the
// floor, so (a) what any pixel gets back in a channel is at most max(albedo, floor) times the
// neighbours' irradiance: a channel darker than the floor is off by at most floor x E; (b) light that
// is not proportional to the albedo (a specular lobe, a mismatch between the albedo the GI used and
// the G-buffer's) is amplified by at most 1 / floor before the filter and rescaled by the
// neighbour's divisor after, not by 1 / ~0.
vec3 denoise_albedo_divisor(vec3 albedo, float albedo_floor) {
    return max(albedo, vec3(albedo_floor));
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

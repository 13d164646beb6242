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

// The a-trous filter's edge-stopping weight of the pair (p, q), the kernel's h left out. It is
// symmetric, w(p, q) = w(q, p), which the mass-preserving normalization of atrous.comp needs: the
// plane test takes the larger of the two points' distances from the other's tangent plane, and
// the luminance test scales |l_p - l_q| by the larger of the two (3 x 3 blurred) variances. With
// p's variance alone (SVGF eq. 5) a bright outlier (large variance) takes in its dark neighbours
// while they (small variance) shut it out, and heavy-tailed noise loses light.
float denoise_atrous_edge_weight(vec3 p, vec3 n_p, float l_p, float variance_p, vec3 q, vec3 n_q, float l_q,
                                 float variance_q, float sigma_plane, float sigma_normal, float sigma_luminance) {
    // Avoids 0 / 0 where the variance is 0 (a noiseless or constant image): only equal luminances pass.
    const float kLuminanceEpsilon = 1e-10;
    float plane = exp(-max(abs(dot(n_p, q - p)), abs(dot(n_q, p - q))) / sigma_plane);
    float luminance_scale = sigma_luminance * sqrt(max(max(variance_p, variance_q), 0.0)) + kLuminanceEpsilon;
    return plane * denoise_normal_weight(n_p, n_q, sigma_normal) * exp(-abs(l_p - l_q) / luminance_scale);
}

#endif

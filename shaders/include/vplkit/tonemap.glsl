#ifndef VPLKIT_TONEMAP_GLSL
#define VPLKIT_TONEMAP_GLSL

// Narkowicz 2015, "ACES Filmic Tone Mapping Curve": a fit of the ACES reference rendering
// transform, (x (a x + b)) / (x (c x + d) + e), clamped to [0, 1].
vec3 aces_filmic(vec3 x) {
    const float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
    // The curve is already clamped to 1 from x ~ 10 on; limiting x keeps x * x finite in float
    // (HDR values reach 1e30 and more: inf / inf would give NaN, and clamp(NaN) is undefined).
    x = min(x, vec3(64.0));
    return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

// IEC 61966-2-1 sRGB transfer function (linear [0, 1] -> encoded [0, 1]).
vec3 linear_to_srgb(vec3 linear) {
    vec3 low = 12.92 * linear;
    vec3 high = 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055;
    return mix(high, low, lessThanEqual(linear, vec3(0.0031308)));
}

#endif

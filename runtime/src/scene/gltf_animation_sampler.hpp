#pragma once
// Keyframe interpolation of one glTF animation channel at a time t (glTF 2.0 3.11 and Appendix
// C): STEP, LINEAR (spherical for rotations) and CUBICSPLINE (Hermite, tangents times the
// keyframe interval). Pure arithmetic on checked keys: reading and checking them from the file
// is gltf_animation's job.

#include <cstddef>
#include <vector>

namespace vplkit::scene::detail {

enum class Interpolation { step, linear, cubic_spline };

// What a channel animates: a rotation (x, y, z, w) is interpolated on the unit sphere and
// normalized; every other path component by component.
enum class AnimatedPath { translation, rotation, scale, weights };

struct KeyedChannel {
    AnimatedPath path = AnimatedPath::translation;
    Interpolation interpolation = Interpolation::linear;
    size_t components = 3;      // 3 (translation, scale), 4 (rotation), the morph target count (weights)
    std::vector<double> times;  // strictly increasing, at least one
    // Per key `components` values; CUBICSPLINE: per key in-tangent, value, out-tangent, each
    // `components` wide (glTF 2.0 3.11's layout, also for weights).
    std::vector<double> values;
};

// The channel's value at time t, `components` wide. t before the first key takes the first key's
// value and t after the last the last's (glTF 2.0 Appendix C: clamped, never extrapolated nor
// wrapped). A rotation comes back normalized.
std::vector<double> sample_channel(const KeyedChannel& channel, double t);

}  // namespace vplkit::scene::detail

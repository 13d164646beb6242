#include "sst_reference.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vplkit::reference {

namespace {

// One float ulp at 1 (twice the unit roundoff): every float operation is charged this much
// relative error, inversesqrt (2 ulp in Vulkan) a few times that.
constexpr double kEps = 0x1p-23;
// The float constants of sst.glsl, so the double frame turns exactly like the float one.
constexpr Double3 kFrameAxis{0.26726124f, 0.53452248f, 0.80178373f};
constexpr Double3 kFrameTangent{0.89442719f, -0.44721360f, 0.0f};

double dot(const Double3& a, const Double3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Double3 cross(const Double3& a, const Double3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Double3 scale(const Double3& a, double s) {
    return {a[0] * s, a[1] * s, a[2] * s};
}
Double3 add(const Double3& a, const Double3& b) {
    return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
Double3 sub(const Double3& a, const Double3& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double max_abs(const Double3& a) {
    return std::max({std::abs(a[0]), std::abs(a[1]), std::abs(a[2])});
}
double max_of(const Double3& a) {
    return std::max({a[0], a[1], a[2]});
}
Double3 to_double(const std::array<float, 3>& a) {
    return {a[0], a[1], a[2]};
}

bool is_suitable(double nu, double sigma_z, const SstThresholds& thresholds) {
    // the SST paper eq. 3, the thesis eq. 5.6
    return nu >= double(thresholds.nu_min) && sigma_z <= double(thresholds.sigma_max);
}

// A child's variance in the parent frame: diagonal of R S R^T, and its error bound.
Double3 variance_in_frame(const SstNodeRef& child, const Double3& t, const Double3& b, const Double3& n) {
    Double3 ct, cb;
    sst_frame(child.normal, ct, cb);
    const Double3& v = child.variance;
    auto along = [&](const Double3& e) {
        double x = dot(e, ct), y = dot(e, cb), z = dot(e, child.normal);
        return x * x * v[0] + y * y * v[1] + z * z * v[2];
    };
    return {along(t), along(b), along(n)};
}

}  // namespace

double sst_intensity(const std::array<float, 3>& flux) {
    double y = 0.2126 * flux[0] + 0.7152 * flux[1] + 0.0722 * flux[2];
    return y > 0.0 ? y : 0.0;
}

void sst_frame(const Double3& n, Double3& t, Double3& b) {
    // Rodrigues' rotation of kFrameTangent by the rotation taking kFrameAxis onto n.
    const double c = dot(kFrameAxis, n);
    Double3 t0 = kFrameTangent;
    if (1.0 + c > kSstFramePoleGuard) {
        const Double3 k = cross(kFrameAxis, n);
        t0 = add(add(scale(kFrameTangent, c), cross(k, kFrameTangent)), scale(k, dot(k, kFrameTangent) / (1.0 + c)));
    }
    const Double3 bt = cross(n, t0);
    b = scale(bt, 1.0 / std::sqrt(dot(bt, bt)));
    t = cross(b, n);
}

namespace {

// How far the float frame of a normal with error `normal_err` may turn: the rotation's
// derivative is <= 1 + 2 / (1 + c) (c = axis . n), its rounding grows the same way, and the
// re-orthonormalization adds a few ulp. Inside the pole guard the frame is a fixed vector made
// orthogonal to n: it moves with n only.
double frame_error(const Double3& n, double normal_err) {
    const double one_plus_c = 1.0 + dot(kFrameAxis, n);
    if (one_plus_c <= kSstFramePoleGuard) return 2 * normal_err + 8 * kEps;
    return (normal_err + 2 * kEps) * (1.0 + 2.0 / one_plus_c) + 8 * kEps;
}

}  // namespace

SstNodeRef sst_empty_node() {
    SstNodeRef node;  // all zero: no VPLs below
    node.merged_normal_length = 0.0;
    return node;
}

SstNodeRef sst_leaf_node(const SstLeaf& leaf, const SstThresholds& thresholds) {
    SstNodeRef node;
    node.mean = to_double(leaf.position);
    node.intensity = sst_intensity(leaf.flux);
    Double3 n = to_double(leaf.normal);
    double n2 = dot(n, n);
    node.normal = n2 > 0.0 ? scale(n, 1.0 / std::sqrt(n2)) : Double3{0.0, 0.0, 1.0};
    node.nu = 1.0;
    node.variance = {0.0, 0.0, 0.0};
    node.sigma_z = 0.0;
    node.suitable = is_suitable(1.0, 0.0, thresholds);
    node.box_lo = node.box_hi = node.mean;
    node.leaf_count = 1;
    node.colour = to_double(leaf.flux);
    node.merged_normal_length = 1.0;
    // Positions are exact; the normal is one float normalization; the luminance a float dot.
    node.error.normal = 4 * kEps;
    node.error.intensity_rel = 4 * kEps;
    return node;
}

SstNodeRef sst_merge(const SstNodeRef& left, const SstNodeRef& right, const SstThresholds& thresholds) {
    // Padding takes no part: a merge with an empty child is the other child.
    if (left.leaf_count == 0) return right;
    if (right.leaf_count == 0) return left;

    SstNodeRef node;
    const double w = left.intensity + right.intensity;
    const double a = w > 0.0 ? left.intensity / w : 0.5;
    const double b = w > 0.0 ? right.intensity / w : 0.5;

    // the SST paper eq. 1 (the thesis eq. 4.1)
    const Double3 d = sub(right.mean, left.mean);
    node.mean = add(left.mean, scale(d, b));
    node.intensity = w;

    // the thesis sec. 4.2.2: normal merged with the same weights, renormalized
    const Double3 m = add(scale(left.normal, a), scale(right.normal, b));
    const double length = std::sqrt(dot(m, m));
    node.merged_normal_length = length;
    if (length >= kSstMinMergedNormalLength) {
        node.normal = scale(m, 1.0 / length);
    } else {
        node.normal = right.intensity > left.intensity ? right.normal : left.normal;
        node.normal_fallback = true;
    }
    // the SST paper sec. 3.2, the thesis eq. 4.3
    const double cosine = dot(left.normal, right.normal);
    node.nu = left.nu * right.nu * std::max(cosine, 0.0);

    // the SST paper eq. 2 in pairwise form: a s1' + b s2' + a b d (.) d in the node frame
    Double3 t, bt;
    sst_frame(node.normal, t, bt);
    const Double3 vl = variance_in_frame(left, t, bt, node.normal);
    const Double3 vr = variance_in_frame(right, t, bt, node.normal);
    const Double3 dl{dot(d, t), dot(d, bt), dot(d, node.normal)};
    for (int k = 0; k < 3; ++k) {
        node.variance[k] = a * vl[k] + b * vr[k] + a * b * dl[k] * dl[k];
    }
    node.sigma_z = std::sqrt(node.variance[2]);

    for (int k = 0; k < 3; ++k) {
        node.box_lo[k] = std::min(left.box_lo[k], right.box_lo[k]);
        node.box_hi[k] = std::max(left.box_hi[k], right.box_hi[k]);
        node.colour[k] = left.colour[k] + right.colour[k];
    }
    node.leaf_count = left.leaf_count + right.leaf_count;
    node.suitable = is_suitable(node.nu, node.sigma_z, thresholds);

    // --- First-order bounds on a float build's error at this node, from its children's. ---
    const SstErrorBound& el = left.error;
    const SstErrorBound& er = right.error;
    SstErrorBound& e = node.error;
    e.intensity_rel = std::max(el.intensity_rel, er.intensity_rel) + kEps;
    e.colour_rel = std::max(el.colour_rel, er.colour_rel) + kEps;
    // a = w1 / w: the error of w1 and of w, and the division.
    const double weight_rel = w > 0.0 ? std::max(el.intensity_rel, er.intensity_rel) + e.intensity_rel + kEps : 0.0;

    // d = p2 - p1 carries both means' errors; mean = p1 + b d adds b's and the roundings.
    const double d_err = el.mean + er.mean + kEps * max_abs(d);
    e.mean = el.mean + b * d_err + (weight_rel + 2 * kEps) * b * max_abs(d) + kEps * max_abs(node.mean);

    // Renormalizing divides the error of m, across m, by |m|.
    const double m_err = a * el.normal + b * er.normal + weight_rel * (a + b) + 3 * kEps;
    if (node.normal_fallback) {
        e.normal = right.intensity > left.intensity ? er.normal : el.normal;
    } else {
        e.normal = m_err / length + 4 * kEps;
    }
    const double one_plus_c = 1.0 + dot(kFrameAxis, node.normal);
    node.decision_ambiguous = left.decision_ambiguous || right.decision_ambiguous ||
                              std::abs(length - kSstMinMergedNormalLength) <= 4 * m_err ||
                              std::abs(one_plus_c - kSstFramePoleGuard) <= 4 * (e.normal + kEps);

    const double cosine_err = el.normal + er.normal + 3 * kEps;
    const double factor = std::max(cosine, 0.0);
    const double factor_err = cosine > -cosine_err ? cosine_err : 0.0;
    e.nu = el.nu * right.nu * factor + left.nu * er.nu * factor + left.nu * right.nu * factor_err + 2 * kEps * node.nu;

    // Frames: the node's from its normal error, each child's from its own.
    const double frame_err = frame_error(node.normal, e.normal);
    // Each squared direction cosine moves by <= 2 (frame errors); they sum to 1 over the
    // child's axes, so the child's own variance error passes through once.
    auto rotated_err = [&](const SstNodeRef& c, const SstErrorBound& ce) {
        double trace = c.variance[0] + c.variance[1] + c.variance[2];
        return ce.variance + (2 * (frame_err + frame_error(c.normal, ce.normal)) + 6 * kEps) * trace;
    };
    const double dl_err = std::sqrt(3.0) * d_err + std::sqrt(dot(d, d)) * (frame_err + 3 * kEps);
    const double dl_max = max_abs(dl);
    const double dl2_err = 2 * dl_max * dl_err + dl_err * dl_err;
    const double terms = std::max(max_of(vl), max_of(vr)) + a * b * dl_max * dl_max;
    e.variance = a * rotated_err(left, el) + b * rotated_err(right, er) + a * b * dl2_err + 2 * weight_rel * terms +
                 4 * kEps * max_of(node.variance);
    return node;
}

std::vector<SstNodeRef> build_sst(std::span<const SstLeaf> leaves, uint32_t count, const SstThresholds& thresholds) {
    const size_t leaf_count = leaves.size();
    if (leaf_count == 0 || (leaf_count & (leaf_count - 1)) != 0) {
        throw std::invalid_argument("sst reference: the leaf count must be a power of two");
    }
    std::vector<SstNodeRef> nodes(2 * leaf_count - 1);
    for (size_t i = 0; i < leaf_count; ++i) {
        nodes[leaf_count - 1 + i] = i < count ? sst_leaf_node(leaves[i], thresholds) : sst_empty_node();
    }
    for (size_t i = leaf_count - 1; i-- > 0;) {
        nodes[i] = sst_merge(nodes[2 * i + 1], nodes[2 * i + 2], thresholds);
    }
    return nodes;
}

DirectMoments direct_moments(std::span<const SstLeaf> vpls) {
    DirectMoments moments;
    Double3 sum{};
    for (const SstLeaf& vpl : vpls) {
        double w = sst_intensity(vpl.flux);
        moments.weight += w;
        sum = add(sum, scale(to_double(vpl.position), w));
    }
    if (!(moments.weight > 0.0)) {
        throw std::invalid_argument("sst reference: direct moments need a positive summed intensity");
    }
    moments.mean = scale(sum, 1.0 / moments.weight);
    double spread = 0.0;
    for (const SstLeaf& vpl : vpls) {
        Double3 x = sub(to_double(vpl.position), moments.mean);
        spread += sst_intensity(vpl.flux) * dot(x, x);
    }
    moments.total_variance = spread / moments.weight;
    return moments;
}

double direct_variance_along(std::span<const SstLeaf> vpls, const Double3& mean, const Double3& axis) {
    double weight = 0.0, spread = 0.0;
    for (const SstLeaf& vpl : vpls) {
        double w = sst_intensity(vpl.flux);
        double x = dot(sub(to_double(vpl.position), mean), axis);
        weight += w;
        spread += w * x * x;
    }
    return weight > 0.0 ? spread / weight : 0.0;
}

}  // namespace vplkit::reference

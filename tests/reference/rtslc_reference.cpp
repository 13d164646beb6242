#include "rtslc_reference.hpp"

#include "direct_light_reference.hpp"

#include <algorithm>
#include <cmath>

namespace vplkit::reference {

namespace {

double dot(const Vec3& a, const Vec3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec3 sub(const Vec3& a, const Vec3& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3 normalized(const Vec3& v) {
    const double l = std::sqrt(dot(v, v));
    return {v[0] / l, v[1] / l, v[2] / l};
}

double distance2_min(const Vec3& x, const Vec3& lo, const Vec3& hi) {
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double d = std::max({lo[k] - x[k], x[k] - hi[k], 0.0});
        d2 += d * d;
    }
    return d2;
}

double distance2_max(const Vec3& x, const Vec3& lo, const Vec3& hi) {
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double d = std::max(std::abs(lo[k] - x[k]), std::abs(hi[k] - x[k]));
        d2 += d * d;
    }
    return d2;
}

}  // namespace

double rtslc_box_cosine_bound(const Vec3& x, const Vec3& n, const Vec3& lo, const Vec3& hi) {
    const Vec3 helper = std::abs(n[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    const Vec3 t = normalized(cross(helper, n));
    const Vec3 b = cross(n, t);
    Vec3 a_lo{1e300, 1e300, 1e300}, a_hi{-1e300, -1e300, -1e300};
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 c =
            sub({(corner & 1) ? hi[0] : lo[0], (corner & 2) ? hi[1] : lo[1], (corner & 4) ? hi[2] : lo[2]}, x);
        const Vec3 local{dot(c, t), dot(c, b), dot(c, n)};
        for (int k = 0; k < 3; ++k) {
            a_lo[k] = std::min(a_lo[k], local[k]);
            a_hi[k] = std::max(a_hi[k], local[k]);
        }
    }
    if (a_hi[2] <= 0.0) {
        return 0.0;
    }
    const double cx = std::max({a_lo[0], -a_hi[0], 0.0});
    const double cy = std::max({a_lo[1], -a_hi[1], 0.0});
    const double r2 = cx * cx + cy * cy;
    return r2 == 0.0 ? 1.0 : a_hi[2] / std::sqrt(r2 + a_hi[2] * a_hi[2]);
}

double rtslc_material_weight(const RtslcShading& s, const RtslcNode& node) {
    const Vec3 centre{0.5 * (node.box_min[0] + node.box_max[0]), 0.5 * (node.box_min[1] + node.box_max[1]),
                      0.5 * (node.box_min[2] + node.box_max[2])};
    const Vec3 to = sub(centre, s.position);
    const Vec3 wi = dot(s.normal, to) > 0.0 ? normalized(to) : s.normal;
    // gi_material_weight lifts the direction by 1e-2 n (and onto the surface first if below it).
    const double lift = std::min(dot(s.normal, wi), 0.0) - 1e-2;
    const Vec3 above = normalized({wi[0] - s.normal[0] * lift, wi[1] - s.normal[1] * lift, wi[2] - s.normal[2] * lift});
    const Vec3 f = gltf_brdf(s.normal, s.wo, above, s.base_color, s.roughness, s.metallic);
    const double weight = 0.2126 * f[0] + 0.7152 * f[1] + 0.0722 * f[2];
    return std::max(weight, 1e-8);
}

double rtslc_node_importance(const RtslcShading& s, const RtslcNode& node) {
    if (node.vpl_count == 0 || node.intensity == 0.0) {
        return 0.0;
    }
    const double cosine = rtslc_box_cosine_bound(s.position, s.normal, node.box_min, node.box_max);
    if (cosine == 0.0) {
        return 0.0;
    }
    return cosine * rtslc_material_weight(s, node) * node.intensity;
}

double rtslc_node_bound(const RtslcShading& s, const RtslcNode& node, double min_distance) {
    const double a = rtslc_node_importance(s, node);
    if (a == 0.0) {
        return 0.0;
    }
    return a / std::max(distance2_min(s.position, node.box_min, node.box_max), min_distance * min_distance);
}

RtslcChildProbability rtslc_child_probability(const RtslcShading& s, const RtslcNode& left, const RtslcNode& right,
                                              double min_distance) {
    const double a_left = rtslc_node_importance(s, left);
    const double a_right = rtslc_node_importance(s, right);
    RtslcChildProbability out;
    if (a_left == 0.0 && a_right == 0.0) {
        out.dead = true;
        return out;
    }
    if (a_left == 0.0 || a_right == 0.0) {
        out.left = a_left == 0.0 ? 0.0 : 1.0;
        return out;
    }
    const double eps2 = min_distance * min_distance;
    auto weight = [&](double a, double d2) { return a / std::max(d2, eps2); };
    const double w_min_l = weight(a_left, distance2_min(s.position, left.box_min, left.box_max));
    const double w_min_r = weight(a_right, distance2_min(s.position, right.box_min, right.box_max));
    const double w_max_l = weight(a_left, distance2_max(s.position, left.box_min, left.box_max));
    const double w_max_r = weight(a_right, distance2_max(s.position, right.box_min, right.box_max));
    out.left = 0.5 * (w_min_l / (w_min_l + w_min_r) + w_max_l / (w_max_l + w_max_r));
    return out;
}

RtslcCut rtslc_select_cut(std::span<const RtslcNode> nodes, uint32_t leaf_count, const RtslcShading& s,
                          double min_distance, uint32_t cut_size) {
    RtslcCut cut;
    std::vector<double> bounds;
    cut.nodes.push_back(0);
    bounds.push_back(rtslc_node_bound(s, nodes[0], min_distance));
    const uint32_t first_leaf = leaf_count - 1;
    while (cut.nodes.size() < cut_size) {
        int best = -1;
        for (size_t i = 0; i < cut.nodes.size(); ++i) {
            if (cut.nodes[i] >= first_leaf) continue;
            if (best < 0 || bounds[i] > bounds[best] || (bounds[i] == bounds[best] && cut.nodes[i] < cut.nodes[best])) {
                best = int(i);
            }
        }
        if (best < 0) break;
        for (size_t i = 0; i < cut.nodes.size(); ++i) {
            if (int(i) == best || cut.nodes[i] >= first_leaf) continue;
            const double gap = bounds[best] == 0.0 ? 1.0 : (bounds[best] - bounds[i]) / bounds[best];
            cut.closest_call = std::min(cut.closest_call, gap);
        }
        const uint32_t node = cut.nodes[best];
        const uint32_t left = 2 * node + 1, right = 2 * node + 2;
        std::vector<uint32_t> children;
        if (nodes[left].vpl_count > 0) children.push_back(left);
        if (nodes[right].vpl_count > 0) children.push_back(right);
        cut.nodes[best] = children[0];
        bounds[best] = rtslc_node_bound(s, nodes[children[0]], min_distance);
        if (children.size() == 2) {
            cut.nodes.push_back(children[1]);
            bounds.push_back(rtslc_node_bound(s, nodes[children[1]], min_distance));
        }
    }
    return cut;
}

std::vector<uint32_t> rtslc_leaves_below(std::span<const RtslcNode> nodes, uint32_t leaf_count, uint32_t node) {
    std::vector<uint32_t> out;
    std::vector<uint32_t> stack{node};
    while (!stack.empty()) {
        const uint32_t n = stack.back();
        stack.pop_back();
        if (nodes[n].vpl_count == 0) continue;
        if (n >= leaf_count - 1) {
            out.push_back(n - (leaf_count - 1));
        } else {
            stack.push_back(2 * n + 1);
            stack.push_back(2 * n + 2);
        }
    }
    return out;
}

Vec3 rtslc_unshadowed_sum(const ShadingPoint& x, const Vec3& camera, std::span<const VplDesc> vpls,
                          double min_distance) {
    const Vec3 wo = normalized(sub(camera, x.position));
    Vec3 sum{};
    for (const VplDesc& vpl : vpls) {
        const Vec3 c = vpl_contribution(x, wo, vpl, min_distance);
        for (int k = 0; k < 3; ++k) sum[k] += c[k];
    }
    return sum;
}

}  // namespace vplkit::reference

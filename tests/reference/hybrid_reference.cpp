#include "hybrid_reference.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace vplkit::reference {

namespace {

Vec3 sub(const Vec3& a, const Vec3& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double dot(const Vec3& a, const Vec3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec3 normalized(const Vec3& v) {
    const double l = std::sqrt(dot(v, v));
    return {v[0] / l, v[1] / l, v[2] / l};
}

bool is_leaf(uint32_t node, uint32_t leaf_count) {
    return node >= leaf_count - 1;
}

uint32_t first_leaf(uint32_t node, uint32_t leaf_count) {
    // Follow left children down to the leaf level.
    while (!is_leaf(node, leaf_count)) node = 2 * node + 1;
    return node - (leaf_count - 1);
}

}  // namespace

double average_corner_cosine(const Vec3& x, const Vec3& n, const Vec3& lo, const Vec3& hi) {
    double sum = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 c = {(corner & 1) ? hi[0] : lo[0], (corner & 2) ? hi[1] : lo[1], (corner & 4) ? hi[2] : lo[2]};
        const Vec3 d = sub(c, x);
        const double len = std::sqrt(dot(d, d));
        if (len > 0.0) sum += std::max(dot(n, d) / len, 0.0);
    }
    return sum / 8.0;
}

double expected_contribution(const ShadingPoint& x, const Vec3& wo, const CutNode& node, double min_distance,
                             double& d2) {
    const Vec3 to_mean = sub(node.mean, x.position);
    d2 = std::max(dot(to_mean, to_mean), min_distance * min_distance);
    if (node.leaf_count == 0 || !(node.intensity > 0.0)) return 0.0;
    const double cosine = average_corner_cosine(x.position, x.normal, node.box_lo, node.box_hi);
    if (cosine == 0.0) return 0.0;
    const double len2 = dot(to_mean, to_mean);
    const Vec3 wi = len2 > 0.0 ? normalized(to_mean) : x.normal;
    // Lifted just above the surface, as gi_material_weight does.
    const double lift = std::min(dot(x.normal, wi), 0.0) - 1e-2;
    const Vec3 above = normalized({wi[0] - x.normal[0] * lift, wi[1] - x.normal[1] * lift, wi[2] - x.normal[2] * lift});
    const Vec3 f = gltf_brdf(x.normal, wo, above, x.base_color, x.roughness, x.metallic);
    const double material = 0.2126 * f[0] + 0.7152 * f[1] + 0.0722 * f[2];
    return material * cosine * node.intensity;
}

std::vector<uint32_t> hybrid_cut(const ShadingPoint& x, const Vec3& wo, const std::function<CutNode(uint32_t)>& node,
                                 uint32_t leaf_count, uint32_t cut_size, double min_distance) {
    struct Entry {
        uint32_t node;
        double priority;  // -1: a leaf
    };
    auto entry = [&](uint32_t index, double a, double d2) {
        return Entry{index, is_leaf(index, leaf_count) ? -1.0 : a / d2};
    };
    std::vector<Entry> cut;
    const CutNode root = node(0);
    if (root.leaf_count > 0) {
        double d2;
        const double a = expected_contribution(x, wo, root, min_distance, d2);
        cut.push_back(entry(0, a, d2));
    }
    while (cut.size() < cut_size) {
        auto best = std::max_element(cut.begin(), cut.end(),
                                     [](const Entry& a, const Entry& b) { return a.priority < b.priority; });
        if (best == cut.end() || best->priority < 0.0) break;
        const uint32_t parent = best->node;
        std::vector<Entry> kept;
        for (uint32_t child : {2 * parent + 1, 2 * parent + 2}) {
            const CutNode data = node(child);
            if (data.leaf_count == 0 || !(data.intensity > 0.0)) continue;  // padding, or no light
            double d2;
            const double a = expected_contribution(x, wo, data, min_distance, d2);
            // Unseen from x (a = 0): kept, never split, so the cut still covers every VPL.
            kept.push_back(a > 0.0 ? entry(child, a, d2) : Entry{child, -1.0});
        }
        cut.erase(best);
        cut.insert(cut.end(), kept.begin(), kept.end());
    }
    std::vector<uint32_t> out;
    for (const Entry& e : cut) out.push_back(e.node);
    std::sort(out.begin(), out.end(),
              [&](uint32_t a, uint32_t b) { return first_leaf(a, leaf_count) < first_leaf(b, leaf_count); });
    return out;
}

}  // namespace vplkit::reference

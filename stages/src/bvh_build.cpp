// Binned SAH build of the triangle BVH (see vplkit/bvh.hpp for the method and its constants).

#include "vplkit/bvh.hpp"

#include "vplkit/error.hpp"

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace vplkit {

namespace {

struct Box {
    glm::vec3 lo{std::numeric_limits<float>::max()};
    glm::vec3 hi{-std::numeric_limits<float>::max()};

    void grow(const glm::vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void grow(const Box& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    bool valid() const { return lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z; }
    // Surface area in double: float products of large extents would lose the small differences
    // between candidate splits.
    double area() const {
        if (!valid()) {
            return 0.0;
        }
        const double dx = double(hi.x) - lo.x, dy = double(hi.y) - lo.y, dz = double(hi.z) - lo.z;
        return 2.0 * (dx * dy + dy * dz + dz * dx);
    }
};

struct Primitive {
    Box box;
    glm::vec3 centroid{};
    uint32_t triangle = 0;  // input triangle index
    bool masked = false;    // build_bvh_split: goes to the masked subtree
};

std::string format_vertex(const glm::vec3& v) {
    char text[96];
    std::snprintf(text, sizeof text, "(%g, %g, %g)", double(v.x), double(v.y), double(v.z));
    return text;
}

bool degenerate(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const double e1x = double(b.x) - a.x, e1y = double(b.y) - a.y, e1z = double(b.z) - a.z;
    const double e2x = double(c.x) - a.x, e2y = double(c.y) - a.y, e2z = double(c.z) - a.z;
    const double nx = e1y * e2z - e1z * e2y;
    const double ny = e1z * e2x - e1x * e2z;
    const double nz = e1x * e2y - e1y * e2x;
    return nx == 0.0 && ny == 0.0 && nz == 0.0;
}

void validate_options(const BvhBuildOptions& o) {
    if (o.bins < 2 || o.bins > 256) {
        throw Error("BVH build: bins = " + std::to_string(o.bins) + " is outside 2..256");
    }
    if (o.max_leaf_triangles < 1 || o.max_leaf_triangles > kBvhMaxLeafTriangles) {
        throw Error("BVH build: max_leaf_triangles = " + std::to_string(o.max_leaf_triangles) + " is outside 1.." +
                    std::to_string(kBvhMaxLeafTriangles));
    }
    if (o.max_depth < 1 || o.max_depth > kBvhMaxDepth) {
        throw Error("BVH build: max_depth = " + std::to_string(o.max_depth) + " is outside 1.." +
                    std::to_string(kBvhMaxDepth) + " (the traversal stack size)");
    }
    if (!(o.traversal_cost > 0.0f) || !std::isfinite(o.traversal_cost) || !(o.triangle_cost > 0.0f) ||
        !std::isfinite(o.triangle_cost)) {
        throw Error("BVH build: traversal_cost and triangle_cost must be finite and positive");
    }
}

class Builder {
public:
    Builder(const BvhBuildOptions& options, std::vector<Primitive>& primitives, Bvh& bvh)
        : options_(options), primitives_(primitives), bvh_(bvh) {}

    // Levels below a node of n triangles that median splits need to reach leaves of
    // max_leaf_triangles: the least L with max_leaf * 2^L >= n.
    uint32_t levels_needed(uint64_t n) const {
        uint32_t levels = 0;
        for (uint64_t capacity = options_.max_leaf_triangles; capacity < n; capacity *= 2) {
            ++levels;
        }
        return levels;
    }

    // Builds the subtree over primitives_[begin, end) at `depth`; returns its node index.
    uint32_t build(uint32_t begin, uint32_t end, uint32_t depth) {
        const uint32_t index = uint32_t(bvh_.nodes.size());
        bvh_.nodes.emplace_back();
        bvh_.depth = std::max(bvh_.depth, depth);

        Box box, centroids;
        for (uint32_t i = begin; i < end; ++i) {
            box.grow(primitives_[i].box);
            centroids.grow(primitives_[i].centroid);
        }
        const uint32_t count = end - begin;
        const double area = box.area();

        Split split = best_split(begin, end, depth, area, centroids);
        const double leaf_cost = double(options_.triangle_cost) * count;
        if (count <= options_.max_leaf_triangles && (!split.found || leaf_cost <= split.cost)) {
            make_leaf(index, box, begin, count, area);
            return index;
        }
        uint32_t mid;
        uint32_t axis;
        if (split.found) {
            axis = split.axis;
            mid = partition(begin, end, split, centroids);
        } else {
            // No SAH split fits the depth cap (or all centroids coincide): the object median
            // halves the node, which needs exactly one level less (levels_needed).
            ++bvh_.median_splits;
            const glm::vec3 extent = centroids.hi - centroids.lo;
            axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
            mid = begin + count / 2;
            std::nth_element(
                primitives_.begin() + begin, primitives_.begin() + mid, primitives_.begin() + end,
                [axis](const Primitive& a, const Primitive& b) { return a.centroid[axis] < b.centroid[axis]; });
        }
        sah_sum_ += area * options_.traversal_cost;
        build(begin, mid, depth + 1);  // lands at index + 1
        const uint32_t second = build(mid, end, depth + 1);
        shaders::BvhNode& node = bvh_.nodes[index];
        store_box(node, box);
        node.index = second;
        node.meta = axis;
        return index;
    }

    // The split layout (vplkit/bvh.hpp): node 0 over the opaque primitives [0, opaque_end) as
    // node 1 and the masked ones [opaque_end, end) as its second child, each built one level down.
    void build_split(uint32_t opaque_end, uint32_t end) {
        bvh_.nodes.emplace_back();
        build(0, opaque_end, 1);  // lands at node 1
        const uint32_t masked = build(opaque_end, end, 1);
        Box box;
        for (uint32_t i = 0; i < end; ++i) {
            box.grow(primitives_[i].box);
        }
        sah_sum_ += box.area() * options_.traversal_cost;
        shaders::BvhNode& root = bvh_.nodes[0];
        store_box(root, box);
        root.index = masked;
        root.meta = 0;  // any axis: the split traversal visits both subtrees in a fixed order
        bvh_.masked_root = masked;
        bvh_.opaque_triangles = opaque_end;
    }

    void finish(const Box& root) {
        const double root_area = root.area();
        bvh_.sah_cost = root_area > 0.0 ? sah_sum_ / root_area : 0.0;
    }

    float padding = 0.0f;

private:
    struct Split {
        bool found = false;
        uint32_t axis = 0;
        uint32_t bin = 0;  // the left child gets bins 0..bin
        double cost = 0.0;
    };

    struct Bin {
        Box box;
        uint32_t count = 0;
    };

    // In double: a float extent can be as small as a denormal, whose float reciprocal overflows.
    uint32_t bin_of(const glm::vec3& centroid, uint32_t axis, const Box& centroids) const {
        const double extent = double(centroids.hi[axis]) - centroids.lo[axis];
        const double offset = (double(centroid[axis]) - centroids.lo[axis]) * (options_.bins / extent);
        return std::min(options_.bins - 1, uint32_t(std::max(offset, 0.0)));
    }

    Split best_split(uint32_t begin, uint32_t end, uint32_t depth, double area, const Box& centroids) {
        Split best;
        const uint32_t count = end - begin;
        if (count < 2 || depth + 1 > options_.max_depth) {
            return best;
        }
        const uint32_t levels_left = options_.max_depth - depth - 1;
        const double inv_area = area > 0.0 ? 1.0 / area : 0.0;
        std::array<Bin, 256> bins;
        std::array<double, 256> right_cost;  // A * N of bins [i, bins)
        for (uint32_t axis = 0; axis < 3; ++axis) {
            if (!(centroids.hi[axis] > centroids.lo[axis])) {
                continue;
            }
            std::fill(bins.begin(), bins.begin() + options_.bins, Bin{});
            for (uint32_t i = begin; i < end; ++i) {
                Bin& bin = bins[bin_of(primitives_[i].centroid, axis, centroids)];
                bin.box.grow(primitives_[i].box);
                ++bin.count;
            }
            Box right;
            uint32_t right_count = 0;
            for (uint32_t i = options_.bins - 1; i > 0; --i) {
                right.grow(bins[i].box);
                right_count += bins[i].count;
                right_cost[i] = right.area() * right_count;
            }
            Box left;
            uint32_t left_count = 0;
            for (uint32_t i = 0; i + 1 < options_.bins; ++i) {
                left.grow(bins[i].box);
                left_count += bins[i].count;
                const uint32_t right_n = count - left_count;
                if (left_count == 0 || right_n == 0) {
                    continue;
                }
                if (levels_needed(std::max(left_count, right_n)) > levels_left) {
                    continue;
                }
                // Area 0 (a node of coplanar, collinear boxes cannot happen for non-degenerate
                // triangles, but stays defined): count-weighted cost.
                const double children =
                    inv_area > 0.0 ? (left.area() * left_count + right_cost[i + 1]) * inv_area : double(count);
                const double cost = options_.traversal_cost + options_.triangle_cost * children;
                if (!best.found || cost < best.cost) {
                    best = {true, axis, i, cost};
                }
            }
        }
        return best;
    }

    uint32_t partition(uint32_t begin, uint32_t end, const Split& split, const Box& centroids) {
        auto middle = std::partition(primitives_.begin() + begin, primitives_.begin() + end, [&](const Primitive& p) {
            return bin_of(p.centroid, split.axis, centroids) <= split.bin;
        });
        return uint32_t(middle - primitives_.begin());
    }

    void store_box(shaders::BvhNode& node, const Box& box) const {
        node.lo = {box.lo.x - padding, box.lo.y - padding, box.lo.z - padding};
        node.hi = {box.hi.x + padding, box.hi.y + padding, box.hi.z + padding};
    }

    void make_leaf(uint32_t index, const Box& box, uint32_t begin, uint32_t count, double area) {
        shaders::BvhNode& node = bvh_.nodes[index];
        store_box(node, box);
        node.index = begin;
        node.meta = kBvhLeafFlag | count;
        ++bvh_.leaf_count;
        sah_sum_ += area * options_.triangle_cost * count;
    }

    const BvhBuildOptions& options_;
    std::vector<Primitive>& primitives_;
    Bvh& bvh_;
    double sah_sum_ = 0.0;
};

// build_bvh, and build_bvh_split when `masked` is not empty.
Bvh build(std::span<const glm::vec3> vertices, std::span<const uint32_t> triangle_ids, std::span<const uint8_t> masked,
          const BvhBuildOptions& options) {
    validate_options(options);
    if (vertices.size() % 3 != 0) {
        throw Error("BVH build: " + std::to_string(vertices.size()) +
                    " vertices is not a whole number of triangles (3 vertices each)");
    }
    const size_t triangle_count = vertices.size() / 3;
    if (triangle_count >= size_t(kBvhCountMask)) {
        throw Error("BVH build: " + std::to_string(triangle_count) + " triangles, at most " +
                    std::to_string(kBvhCountMask - 1) + " are supported");
    }
    if (!triangle_ids.empty() && triangle_ids.size() != triangle_count) {
        throw Error("BVH build: " + std::to_string(triangle_ids.size()) + " triangle ids for " +
                    std::to_string(triangle_count) + " triangles");
    }

    Bvh bvh;
    bvh.input_triangles = uint32_t(triangle_count);
    std::vector<Primitive> primitives;
    primitives.reserve(triangle_count);
    float scale = 0.0f;
    for (size_t t = 0; t < triangle_count; ++t) {
        for (int k = 0; k < 3; ++k) {
            const glm::vec3& v = vertices[3 * t + k];
            for (int axis = 0; axis < 3; ++axis) {
                if (!std::isfinite(v[axis])) {
                    throw Error("BVH build: triangle " + std::to_string(t) + " has a non-finite vertex " +
                                std::to_string(k) + " " + format_vertex(v));
                }
                if (!(std::fabs(v[axis]) < kBvhMaxCoordinate)) {
                    throw Error("BVH build: triangle " + std::to_string(t) + " vertex " + std::to_string(k) + " " +
                                format_vertex(v) +
                                " lies beyond +-2^32, where the float intersection test could overflow");
                }
            }
        }
        if (!triangle_ids.empty() && triangle_ids[t] == kBvhNoHit) {
            throw Error("BVH build: triangle " + std::to_string(t) + " has id 0xffffffff, reserved for 'no hit'");
        }
        const glm::vec3& a = vertices[3 * t];
        const glm::vec3& b = vertices[3 * t + 1];
        const glm::vec3& c = vertices[3 * t + 2];
        if (degenerate(a, b, c)) {
            ++bvh.degenerate_triangles;
            continue;
        }
        Primitive p;
        p.box.grow(a);
        p.box.grow(b);
        p.box.grow(c);
        p.centroid = 0.5f * (p.box.lo + p.box.hi);
        p.triangle = uint32_t(t);
        p.masked = !masked.empty() && masked[t] != 0;
        primitives.push_back(p);
        for (int axis = 0; axis < 3; ++axis) {
            scale = std::max({scale, std::fabs(p.box.lo[axis]), std::fabs(p.box.hi[axis])});
        }
    }

    if (primitives.empty()) {
        shaders::BvhNode root{};
        root.index = 0;
        root.meta = kBvhLeafFlag;  // a leaf of no triangles: nothing to hit
        bvh.nodes.push_back(root);
        bvh.leaf_count = 1;
        bvh.scene_scale = kBvhMinScale;
        return bvh;
    }

    const uint32_t masked_count =
        uint32_t(std::count_if(primitives.begin(), primitives.end(), [](const Primitive& p) { return p.masked; }));
    const uint32_t opaque_count = uint32_t(primitives.size()) - masked_count;
    Builder builder(options, primitives, bvh);
    // No split unless both kinds exist. The split costs the common root's level: where the deeper
    // subtree would not fit below it, one tree (correct: the masked triangles are then tested in
    // the one loop).
    const bool split = opaque_count > 0 && masked_count > 0 &&
                       builder.levels_needed(std::max(opaque_count, masked_count)) + 1 <= options.max_depth;
    if (split) {
        // Opaque primitives first, masked ones after (the split layout).
        std::stable_partition(primitives.begin(), primitives.end(), [](const Primitive& p) { return !p.masked; });
    }
    if (builder.levels_needed(primitives.size()) > options.max_depth) {
        throw Error("BVH build: " + std::to_string(primitives.size()) + " triangles do not fit in leaves of " +
                    std::to_string(options.max_leaf_triangles) + " within max_depth " +
                    std::to_string(options.max_depth));
    }
    builder.padding = scale * kBvhBoxPadding;
    bvh.nodes.reserve(2 * primitives.size() + 1);
    if (split) {
        builder.build_split(opaque_count, uint32_t(primitives.size()));
    } else {
        builder.build(0, uint32_t(primitives.size()), 0);
    }
    Box root;
    for (const Primitive& p : primitives) {
        root.grow(p.box);
    }
    builder.finish(root);

    bvh.triangles.resize(primitives.size());
    for (size_t i = 0; i < primitives.size(); ++i) {
        const uint32_t t = primitives[i].triangle;
        shaders::BvhTriangle& tri = bvh.triangles[i];
        tri = {};
        const glm::vec3& a = vertices[3 * t];
        const glm::vec3& b = vertices[3 * t + 1];
        const glm::vec3& c = vertices[3 * t + 2];
        tri.v0 = {a.x, a.y, a.z};
        tri.v1 = {b.x, b.y, b.z};
        tri.v2 = {c.x, c.y, c.z};
        tri.id = triangle_ids.empty() ? t : triangle_ids[t];
    }

    const shaders::BvhNode& top = bvh.nodes[0];
    float stored = kBvhMinScale;
    for (float c : {top.lo.x, top.lo.y, top.lo.z, top.hi.x, top.hi.y, top.hi.z}) {
        stored = std::max(stored, std::fabs(c));
    }
    bvh.scene_scale = stored;
    return bvh;
}

}  // namespace

Bvh build_bvh(std::span<const glm::vec3> vertices, std::span<const uint32_t> triangle_ids,
              const BvhBuildOptions& options) {
    return build(vertices, triangle_ids, {}, options);
}

Bvh build_bvh_split(std::span<const glm::vec3> vertices, std::span<const uint8_t> masked,
                    std::span<const uint32_t> triangle_ids, const BvhBuildOptions& options) {
    if (masked.size() != vertices.size() / 3 || vertices.size() % 3 != 0) {
        throw Error("BVH build: " + std::to_string(masked.size()) + " masked flags for " +
                    std::to_string(vertices.size()) + " vertices (one flag per triangle of 3 vertices)");
    }
    return build(vertices, triangle_ids, masked, options);
}

}  // namespace vplkit

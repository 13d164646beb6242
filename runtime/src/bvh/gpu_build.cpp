// GpuBvhBuild: the checks build_bvh makes on the host, then the GPU build or refit.

#include "vplkit/bvh_gpu_build.hpp"

#include "device_buffers.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/shaders/bvh_refit_gather.hpp"
#include "vplkit/stages/binding_uses.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace vplkit {

namespace {

// The most triangles the GPU build puts in one (capped) leaf.
constexpr uint32_t kLargestLeaf = 65535;

std::string format_vertex(const glm::vec3& v) {
    char text[96];
    std::snprintf(text, sizeof text, "(%g, %g, %g)", double(v.x), double(v.y), double(v.z));
    return text;
}

// As build_bvh: finite coordinates below kBvhMaxCoordinate.
void check_vertex(const glm::vec3& v, size_t triangle, int k) {
    for (int axis = 0; axis < 3; ++axis) {
        if (!std::isfinite(v[axis])) {
            throw Error("GPU BVH build: triangle " + std::to_string(triangle) + " has a non-finite vertex " +
                        std::to_string(k) + " " + format_vertex(v));
        }
        if (!(std::fabs(v[axis]) < kBvhMaxCoordinate)) {
            throw Error("GPU BVH build: triangle " + std::to_string(triangle) + " vertex " + std::to_string(k) + " " +
                        format_vertex(v) + " lies beyond +-2^32, where the float intersection test could overflow");
        }
    }
}

// As build_bvh: zero area when the double cross product of two edges is exactly zero.
bool degenerate(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const double e1x = double(b.x) - a.x, e1y = double(b.y) - a.y, e1z = double(b.z) - a.z;
    const double e2x = double(c.x) - a.x, e2y = double(c.y) - a.y, e2z = double(c.z) - a.z;
    return e1y * e2z - e1z * e2y == 0.0 && e1z * e2x - e1x * e2z == 0.0 && e1x * e2y - e1y * e2x == 0.0;
}

void check_range(const Context& context, VkDeviceSize bytes, const char* what) {
    const uint64_t limit = context.info().max_storage_buffer_range;
    if (bytes > limit) {
        throw Error(std::string("GPU BVH build: the ") + what + " need " + std::to_string(bytes) +
                    " bytes, more than this device's maxStorageBufferRange of " + std::to_string(limit));
    }
}

Buffer storage(Context& context, VkDeviceSize bytes, const char* name) {
    check_range(context, bytes, name);
    return Buffer::create(context, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, name);
}

void set(shaders::vec3& out, const glm::vec3& v) {
    out = {v.x, v.y, v.z};
}

}  // namespace

GpuBvhBuild::GpuBvhBuild(Context& context, std::span<const glm::vec3> vertices, std::span<const uint32_t> triangle_ids,
                         const stages::BvhGpuBuildOptions& options, const GpuBvhAlphaRecords* alpha, bool addressed)
    : context_(&context), options_(options) {
    if (vertices.size() % 3 != 0) {
        throw Error("GPU BVH build: " + std::to_string(vertices.size()) +
                    " vertices is not a whole number of triangles (3 vertices each)");
    }
    const size_t triangle_count = vertices.size() / 3;
    if (triangle_count >= size_t(kBvhCountMask)) {
        throw Error("GPU BVH build: " + std::to_string(triangle_count) + " triangles, at most " +
                    std::to_string(kBvhCountMask - 1) + " are supported");
    }
    if (!triangle_ids.empty() && triangle_ids.size() != triangle_count) {
        throw Error("GPU BVH build: " + std::to_string(triangle_ids.size()) + " triangle ids for " +
                    std::to_string(triangle_count) + " triangles");
    }
    if (alpha && (alpha->triangle_records.size() != triangle_count || alpha->words.size() < kBvhHeaderWords)) {
        throw Error("GPU BVH build: " + std::to_string(alpha->triangle_records.size()) + " alpha records for " +
                    std::to_string(triangle_count) + " triangles (and " + std::to_string(alpha->words.size()) +
                    " words: the " + std::to_string(kBvhHeaderWords) + " of the header at least)");
    }
    stats_.input_triangles = uint32_t(triangle_count);
    for (size_t t = 0; t < triangle_count; ++t) {
        for (int k = 0; k < 3; ++k) {
            check_vertex(vertices[3 * t + k], t, k);
        }
        const uint32_t id = triangle_ids.empty() ? uint32_t(t) : triangle_ids[t];
        if (id == kBvhNoHit) {
            throw Error("GPU BVH build: triangle " + std::to_string(t) + " has id 0xffffffff, reserved for 'no hit'");
        }
        if (degenerate(vertices[3 * t], vertices[3 * t + 1], vertices[3 * t + 2])) {
            ++stats_.degenerate_triangles;
            continue;
        }
        kept_.push_back(uint32_t(t));
        shaders::BvhTriangle record{};
        record.id = id;
        record.alpha = alpha ? alpha->triangle_records[t] : 0u;
        records_.push_back(record);
    }

    if (kept_.empty()) {
        // The empty leaf, exactly what build_bvh and upload_bvh give.
        bvh_ = upload_bvh(context, build_bvh({}));
        stats_.node_count = 1;
        stats_.leaf_count = 1;
        return;
    }
    const uint32_t count = uint32_t(kept_.size());
    const stages::BvhGpuBuildSizes sizes = stages::bvh_gpu_build_sizes(count);
    // Past a binding's range, the build reads and writes its per-triangle and per-slot buffers at
    // their addresses (slower on lavapipe, so only then), and the traversal reads the BVH so.
    const uint64_t range = context.info().max_storage_buffer_range;
    const uint64_t alpha_bytes = alpha ? uint64_t(alpha->words.size()) * sizeof(uint32_t) : 0;
    bvh_.addressed = sizes.nodes > range || sizes.triangles > range || alpha_bytes > range;
    addressed_ =
        addressed || bvh_.addressed || sizes.input > range || sizes.build_nodes > range || sizes.build_links > range;
    bvh_.nodes = create_bvh_buffer(context, sizes.nodes, "nodes", "GPU BVH build");
    bvh_.triangles = create_bvh_buffer(context, sizes.triangles, "triangles", "GPU BVH build");
    bvh_.alpha = upload_bvh_alpha(context, bvh_.nodes, bvh_.triangles,
                                  alpha ? std::span<const uint32_t>(alpha->words) : std::span<const uint32_t>{},
                                  "GPU BVH build");
    bvh_.alpha_tests = alpha != nullptr;
    bvh_.triangle_count = count;
    input_ = create_bvh_buffer(context, sizes.input, "build input", "GPU BVH build");
    info_ = storage(context, sizes.info, "bvh build info");
    build_nodes_ = create_bvh_buffer(context, sizes.build_nodes, "build nodes", "GPU BVH build");
    build_links_ = create_bvh_buffer(context, sizes.build_links, "build links", "GPU BVH build");
    keys_ = storage(context, sizes.keys, "bvh build keys");
    order_ = storage(context, sizes.order, "bvh build order");
    stages::RadixSortOptions sort;
    sort.key_bits = stages::kBvhBuildKeyBits;
    sorter_ = std::make_unique<stages::RadixSorter>(context, count, sort);
    upload_input(vertices);
    run(true);
}

void GpuBvhBuild::upload_input(std::span<const glm::vec3> vertices) {
    for (size_t i = 0; i < kept_.size(); ++i) {
        const size_t t = kept_[i];
        set(records_[i].v0, vertices[3 * t]);
        set(records_[i].v1, vertices[3 * t + 1]);
        set(records_[i].v2, vertices[3 * t + 2]);
    }
    input_.upload(records_);
}

stages::BvhGpuBuildBuffers GpuBvhBuild::buffers() const {
    return {input_,    bvh_.nodes,   bvh_.triangles,
            info_,     build_nodes_, build_links_,
            keys_,     order_,       bvh_.alpha_tests ? BufferView(bvh_.alpha) : BufferView{},
            addressed_};
}

void GpuBvhBuild::add_build_passes(StepList& passes) {
    if (!kept_.empty()) {
        stages::add_bvh_gpu_build_passes(*context_, passes, *sorter_, buffers(), uint32_t(kept_.size()), options_);
    }
}

void GpuBvhBuild::add_refit_passes(StepList& passes) {
    if (!kept_.empty()) {
        stages::add_bvh_gpu_refit_passes(*context_, passes, buffers(), uint32_t(kept_.size()), options_);
    }
}

void GpuBvhBuild::run(bool build) {
    PassList passes(build ? "gpu bvh build" : "gpu bvh refit");
    if (build) {
        add_build_passes(passes);
    } else {
        add_refit_passes(passes);
    }
    passes.run(*context_);
    timings_ = passes.timings();
    stats_.gpu_ms = passes.total_gpu_ms();
    read_info(build);
}

void GpuBvhBuild::read_info(bool build) {
    const shaders::BvhBuildInfo info = info_.download<shaders::BvhBuildInfo>(1).at(0);
    bvh_.node_count = info.node_count;
    bvh_.scene_scale = info.scene_scale;
    if (build) {
        stats_.node_count = info.node_count;
        stats_.leaf_count = info.leaf_count;
        stats_.depth = info.depth;
        stats_.lbvh_depth = info.lbvh_depth;
        stats_.largest_leaf = info.largest_leaf;
        stats_.capped_leaves = info.capped_leaves;
        stats_.masked_root = info.masked_root;
        // The leaf pass loops over a leaf's triangles, and lavapipe ends a loop after 65,535
        // iterations: a larger (capped) leaf may have lost triangles.
        if (info.largest_leaf > kLargestLeaf) {
            throw Error("GPU BVH build: a leaf at depth " + std::to_string(options_.max_depth) + " holds " +
                        std::to_string(info.largest_leaf) + " triangles (the LBVH is " +
                        std::to_string(info.lbvh_depth) + " deep), more than " + std::to_string(kLargestLeaf) +
                        "; build this scene on the host (build_bvh)");
        }
    }
}

void GpuBvhBuild::refit(std::span<const glm::vec3> vertices) {
    if (vertices.size() != size_t(stats_.input_triangles) * 3) {
        throw Error("GPU BVH refit: " + std::to_string(vertices.size()) + " vertices, the build had " +
                    std::to_string(size_t(stats_.input_triangles) * 3));
    }
    for (size_t t = 0; t < stats_.input_triangles; ++t) {
        for (int k = 0; k < 3; ++k) {
            check_vertex(vertices[3 * t + k], t, k);
        }
    }
    if (kept_.empty()) {
        return;
    }
    upload_input(vertices);
    run(false);
}

void GpuBvhBuild::add_refit_passes(StepList& passes, const BufferView& scene_vertices,
                                   const BufferView& scene_indices) {
    if (kept_.empty()) return;
    if (addressed_) {
        throw Error(
            "GPU BVH refit: this build reads its input at device addresses (past maxStorageBufferRange); "
            "the refit from the scene's buffers binds it: refit from host vertices");
    }
    const VkDeviceSize index_bytes = VkDeviceSize(stats_.input_triangles) * 3 * sizeof(uint32_t);
    if (scene_indices.size < index_bytes) {
        throw Error("GPU BVH refit: '" + scene_indices.name + "' holds " + std::to_string(scene_indices.size) +
                    " bytes, the build's " + std::to_string(stats_.input_triangles) + " triangles need " +
                    std::to_string(index_bytes));
    }
    if (scene_vertices.size < sizeof(shaders::SceneVertex)) {
        throw Error("GPU BVH refit: no vertices in '" + scene_vertices.name + "'");
    }
    check_range(*context_, scene_vertices.size, "scene vertices");
    check_range(*context_, scene_indices.size, "scene indices");
    if (!kept_triangles_) {
        kept_triangles_ = storage(*context_, kept_.size() * sizeof(uint32_t), "bvh kept triangles");
        kept_triangles_.upload(kept_);
    }
    passes.names({scene_vertices, scene_indices});
    namespace shader = shaders::bvh_refit_gather;
    shader::Bindings bindings;
    bindings.scene_vertices = scene_vertices.descriptor();
    bindings.scene_indices = scene_indices.descriptor();
    bindings.kept_triangles = BufferView(kept_triangles_).descriptor();
    bindings.input_triangles = BufferView(input_).descriptor();
    shader::Push push{};
    push.triangle_count = uint32_t(kept_.size());
    stages::add_dispatch<shader::Module>(passes, "bvh refit gather", context_->pipeline<shader::Pipeline>(), bindings,
                                         push, push.triangle_count);
    add_refit_passes(passes);
}

void GpuBvhBuild::finish_refit(double gpu_ms) {
    if (kept_.empty()) return;
    stats_.gpu_ms = gpu_ms;
    read_info(false);
}

}  // namespace vplkit

#include "scene/gltf_accessors.hpp"

#include "vplkit/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace vplkit::scene::detail {
namespace {

size_t component_size(int component_type) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return 2;
        case TINYGLTF_COMPONENT_TYPE_INT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return 4;
        default:
            return 0;
    }
}

std::string component_name(int component_type) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            return "BYTE";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return "UNSIGNED_BYTE";
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            return "SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return "UNSIGNED_SHORT";
        case TINYGLTF_COMPONENT_TYPE_INT:
            return "INT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return "UNSIGNED_INT";
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return "FLOAT";
        default:
            return "component type " + std::to_string(component_type);
    }
}

size_t type_components(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return 1;
        case TINYGLTF_TYPE_VEC2:
            return 2;
        case TINYGLTF_TYPE_VEC3:
            return 3;
        case TINYGLTF_TYPE_VEC4:
            return 4;
        case TINYGLTF_TYPE_MAT2:
            return 4;
        case TINYGLTF_TYPE_MAT3:
            return 9;
        case TINYGLTF_TYPE_MAT4:
            return 16;
        default:
            return 0;
    }
}

std::string type_name(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return "SCALAR";
        case TINYGLTF_TYPE_VEC2:
            return "VEC2";
        case TINYGLTF_TYPE_VEC3:
            return "VEC3";
        case TINYGLTF_TYPE_VEC4:
            return "VEC4";
        case TINYGLTF_TYPE_MAT2:
            return "MAT2";
        case TINYGLTF_TYPE_MAT3:
            return "MAT3";
        case TINYGLTF_TYPE_MAT4:
            return "MAT4";
        default:
            return "type " + std::to_string(type);
    }
}

// Checks that `count` elements of `element_size` bytes, `stride` apart, starting at `offset`,
// fit in `bytes`; `owner` names the reader ("accessor 3 (POSITION of ...)").
void check_fits(const GltfSource& source, std::span<const uint8_t> bytes, size_t offset, size_t count,
                size_t element_size, size_t stride, const std::string& owner, const std::string& container) {
    if (count == 0) return;
    const size_t size = bytes.size();
    const bool fits =
        offset <= size && element_size <= size - offset && (count - 1) <= (size - offset - element_size) / stride;
    if (!fits) {
        // In 128 bits: a corrupt count or stride must not wrap around in the message either.
        const unsigned __int128 end =
            (unsigned __int128)offset + (unsigned __int128)(count - 1) * stride + element_size;
        const auto end_text = end > UINT64_MAX ? std::string("more than 2^64") : std::to_string(uint64_t(end));
        source.fail(owner + " reads " + std::to_string(count) + " element(s) of " + std::to_string(element_size) +
                    " bytes (stride " + std::to_string(stride) + ") from byte " + std::to_string(offset) +
                    ", up to byte " + end_text + ", but " + container + " has only " + std::to_string(size) + " bytes");
    }
}

// Reads one component as float, applying glTF's normalization rules for integer types.
float read_component(const uint8_t* p, int component_type, bool normalized) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float v;
            std::memcpy(&v, p, 4);
            return v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return normalized ? float(*p) / 255.0f : float(*p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? float(v) / 65535.0f : float(v);
        }
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            int8_t v;
            std::memcpy(&v, p, 1);
            return normalized ? std::max(float(v) / 127.0f, -1.0f) : float(v);
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            int16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? std::max(float(v) / 32767.0f, -1.0f) : float(v);
        }
        default:
            return 0.0f;
    }
}

uint32_t read_index(const uint8_t* p, int component_type) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return *p;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return v;
        }
        default: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return v;
        }
    }
}

const tinygltf::Accessor& get_accessor(const GltfSource& source, int index, const std::string& what) {
    if (index < 0 || size_t(index) >= source.model.accessors.size()) {
        source.fail(what + " refers to accessor " + std::to_string(index) + ", but the file has " +
                    std::to_string(source.model.accessors.size()) + " accessors");
    }
    return source.model.accessors[size_t(index)];
}

// More elements than any real scene has: a corrupt count, which would otherwise allocate
// gigabytes of zeros for an accessor without a bufferView before anything else fails.
constexpr size_t kMaxAccessorCount = size_t(1) << 28;

size_t checked_count(const GltfSource& source, const tinygltf::Accessor& accessor, const std::string& owner) {
    if (accessor.count == 0) source.fail(owner + " has count 0 (glTF 2.0 requires at least 1)");
    if (accessor.count > kMaxAccessorCount) {
        source.fail(owner + " has count " + std::to_string(accessor.count) + ", more than vplkit's limit of 2^28");
    }
    return accessor.count;
}

std::string admitted_text(uint32_t admits) {
    std::vector<std::string> kinds;
    if (admits & kAdmitFloat) kinds.push_back("FLOAT");
    if (admits & kAdmitNormalizedUnsigned) kinds.push_back("normalized UNSIGNED_BYTE / UNSIGNED_SHORT");
    if (admits & kAdmitNormalizedSigned) kinds.push_back("normalized BYTE / SHORT");
    if (admits & kAdmitIntegers) kinds.push_back("BYTE / UNSIGNED_BYTE / SHORT / UNSIGNED_SHORT");
    std::string out;
    for (size_t i = 0; i < kinds.size(); ++i) out += (i == 0 ? "" : i + 1 == kinds.size() ? " or " : ", ") + kinds[i];
    return out;
}

bool admitted(int ct, bool normalized, uint32_t admits) {
    const bool unsigned_small =
        ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    const bool signed_small = ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_SHORT;
    if (ct == TINYGLTF_COMPONENT_TYPE_FLOAT) return admits & kAdmitFloat;
    if (normalized && unsigned_small) return admits & kAdmitNormalizedUnsigned;
    if (normalized && signed_small) return admits & kAdmitNormalizedSigned;
    if (!normalized && (unsigned_small || signed_small)) return admits & kAdmitIntegers;
    return false;
}

}  // namespace

bool quantized(const GltfSource& source) {
    const auto& used = source.model.extensionsUsed;
    return std::find(used.begin(), used.end(), "KHR_mesh_quantization") != used.end();
}

std::vector<float> read_floats(const GltfSource& source, int index, size_t components, uint32_t core,
                               uint32_t with_quantization, const std::string& what) {
    const tinygltf::Accessor& accessor = get_accessor(source, index, what);
    const std::string owner = "accessor " + std::to_string(index) + " (" + what + ")";
    if (type_components(accessor.type) != components || accessor.type == TINYGLTF_TYPE_MAT2 ||
        accessor.type == TINYGLTF_TYPE_MAT3) {
        source.fail(owner + " has type " + type_name(accessor.type) + ", expected " +
                    (components == 1   ? "SCALAR"
                     : components == 2 ? "VEC2"
                     : components == 3 ? "VEC3"
                     : components == 4 ? "VEC4"
                                       : "MAT4"));
    }
    const int ct = accessor.componentType;
    const uint32_t admits = core | with_quantization;
    const uint32_t allowed = quantized(source) ? admits : core;
    if (!admitted(ct, accessor.normalized, allowed)) {
        const bool needs_extension = admitted(ct, accessor.normalized, admits);
        source.fail(owner + " has " + (accessor.normalized ? "normalized " : "") + component_name(ct) +
                    " components; " +
                    (needs_extension ? "only KHR_mesh_quantization allows them, and the file does not list it in "
                                       "extensionsUsed (allowed: " +
                                           admitted_text(core) + ")"
                                     : "glTF allows " + admitted_text(admits) + " here"));
    }
    const size_t csize = component_size(ct);
    const size_t element_size = csize * components;
    const size_t count = checked_count(source, accessor, owner);

    std::vector<float> out;
    out.resize(count * components, 0.0f);  // an accessor without a bufferView is all zeros
    if (accessor.bufferView >= 0) {
        const auto bytes = buffer_view_bytes(source, accessor.bufferView, owner);
        const size_t view_stride = source.model.bufferViews[size_t(accessor.bufferView)].byteStride;
        if (view_stride != 0 && view_stride < element_size) {
            source.fail(owner + ": bufferView " + std::to_string(accessor.bufferView) + " has byteStride " +
                        std::to_string(view_stride) + ", smaller than the " + std::to_string(element_size) +
                        "-byte element");
        }
        const size_t stride = view_stride != 0 ? view_stride : element_size;
        check_fits(source, bytes, accessor.byteOffset, count, element_size, stride, owner,
                   "bufferView " + std::to_string(accessor.bufferView));
        const uint8_t* base = bytes.data() + accessor.byteOffset;
        for (size_t i = 0; i < count; ++i) {
            const uint8_t* element = base + i * stride;
            for (size_t c = 0; c < components; ++c) {
                out[i * components + c] = read_component(element + c * csize, ct, accessor.normalized);
            }
        }
    }

    if (accessor.sparse.isSparse) {
        const auto& sparse = accessor.sparse;
        const std::string sparse_owner = owner + " sparse";
        if (sparse.count < 1 || size_t(sparse.count) > count) {
            source.fail(sparse_owner + " count is " + std::to_string(sparse.count) + ", not in 1.." +
                        std::to_string(count));
        }
        const int ict = sparse.indices.componentType;
        if (ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
            source.fail(sparse_owner + " indices have " + component_name(ict) + " components");
        }
        if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0) {
            source.fail(sparse_owner + " has a negative byteOffset");
        }
        const size_t n = size_t(sparse.count);
        const auto index_bytes = buffer_view_bytes(source, sparse.indices.bufferView, sparse_owner + " indices");
        const auto value_bytes = buffer_view_bytes(source, sparse.values.bufferView, sparse_owner + " values");
        const size_t isize = component_size(ict);
        check_fits(source, index_bytes, size_t(sparse.indices.byteOffset), n, isize, isize, sparse_owner + " indices",
                   "bufferView " + std::to_string(sparse.indices.bufferView));
        check_fits(source, value_bytes, size_t(sparse.values.byteOffset), n, element_size, element_size,
                   sparse_owner + " values", "bufferView " + std::to_string(sparse.values.bufferView));
        for (size_t k = 0; k < n; ++k) {
            const uint32_t target = read_index(index_bytes.data() + size_t(sparse.indices.byteOffset) + k * isize, ict);
            if (target >= count) {
                source.fail(sparse_owner + " index " + std::to_string(k) + " is " + std::to_string(target) +
                            ", outside the accessor's " + std::to_string(count) + " elements");
            }
            const uint8_t* element = value_bytes.data() + size_t(sparse.values.byteOffset) + k * element_size;
            for (size_t c = 0; c < components; ++c) {
                out[target * components + c] = read_component(element + c * csize, ct, accessor.normalized);
            }
        }
    }
    return out;
}

void GltfSource::fail(const std::string& problem) const {
    throw Error(file + ": " + problem);
}

std::span<const uint8_t> buffer_view_bytes(const GltfSource& source, int index, const std::string& what) {
    const auto& model = source.model;
    if (index < 0 || size_t(index) >= model.bufferViews.size()) {
        source.fail(what + " refers to bufferView " + std::to_string(index) + ", but the file has " +
                    std::to_string(model.bufferViews.size()) + " bufferViews");
    }
    const tinygltf::BufferView& view = model.bufferViews[size_t(index)];
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size()) {
        source.fail("bufferView " + std::to_string(index) + " refers to buffer " + std::to_string(view.buffer) +
                    ", but the file has " + std::to_string(model.buffers.size()) + " buffers");
    }
    const tinygltf::Buffer& buffer = model.buffers[size_t(view.buffer)];
    const size_t size = buffer.data.size();
    if (view.byteOffset > size || view.byteLength > size - view.byteOffset) {
        const std::string name =
            buffer.uri.empty() || buffer.uri.rfind("data:", 0) == 0 ? std::string() : " ('" + buffer.uri + "')";
        source.fail("bufferView " + std::to_string(index) + " (used by " + what + ") spans bytes " +
                    std::to_string(view.byteOffset) + " + " + std::to_string(view.byteLength) + " of buffer " +
                    std::to_string(view.buffer) + name + ", which has only " + std::to_string(size) + " bytes");
    }
    return {buffer.data.data() + view.byteOffset, view.byteLength};
}

size_t accessor_count(const GltfSource& source, int index, const std::string& what) {
    return get_accessor(source, index, what).count;
}

namespace {

template <typename Vec>
std::vector<Vec> as_vectors(const std::vector<float>& floats) {
    std::vector<Vec> out(floats.size() * sizeof(float) / sizeof(Vec));
    std::memcpy(out.data(), floats.data(), floats.size() * sizeof(float));
    return out;
}

}  // namespace

std::vector<glm::vec3> read_positions(const GltfSource& source, int accessor, const std::string& what) {
    return as_vectors<glm::vec3>(read_floats(source, accessor, 3, kAdmitFloat,
                                             kAdmitNormalizedUnsigned | kAdmitNormalizedSigned | kAdmitIntegers, what));
}

std::vector<glm::vec3> read_normals(const GltfSource& source, int accessor, const std::string& what) {
    return as_vectors<glm::vec3>(read_floats(source, accessor, 3, kAdmitFloat, kAdmitNormalizedSigned, what));
}

std::vector<glm::vec4> read_tangents(const GltfSource& source, int accessor, const std::string& what) {
    return as_vectors<glm::vec4>(read_floats(source, accessor, 4, kAdmitFloat, kAdmitNormalizedSigned, what));
}

std::vector<glm::vec2> read_texcoords(const GltfSource& source, int accessor, const std::string& what) {
    return as_vectors<glm::vec2>(read_floats(source, accessor, 2, kAdmitFloat | kAdmitNormalizedUnsigned,
                                             kAdmitNormalizedSigned | kAdmitIntegers, what));
}

std::vector<glm::vec3> read_target_positions(const GltfSource& source, int accessor, const std::string& what) {
    return as_vectors<glm::vec3>(
        read_floats(source, accessor, 3, kAdmitFloat, kAdmitNormalizedSigned | kAdmitIntegers, what));
}

std::vector<glm::vec3> read_target_directions(const GltfSource& source, int accessor, const std::string& what) {
    return as_vectors<glm::vec3>(read_floats(source, accessor, 3, kAdmitFloat, kAdmitNormalizedSigned, what));
}

std::vector<glm::uvec4> read_joints(const GltfSource& source, int accessor, const std::string& what) {
    const tinygltf::Accessor& a = get_accessor(source, accessor, what);
    const int ct = a.componentType;
    if (a.normalized || (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)) {
        source.fail("accessor " + std::to_string(accessor) + " (" + what + ") has " +
                    (a.normalized ? "normalized " : "") + component_name(ct) +
                    " components; joint indices must be UNSIGNED_BYTE or UNSIGNED_SHORT (not normalized)");
    }
    // Read as unnormalized integers: exact in float up to 65535.
    const auto floats = read_floats(source, accessor, 4, kAdmitIntegers, 0, what);
    std::vector<glm::uvec4> out(floats.size() / 4);
    for (size_t i = 0; i < out.size(); ++i) {
        for (int c = 0; c < 4; ++c) out[i][c] = uint32_t(floats[4 * i + size_t(c)]);
    }
    return out;
}

std::vector<glm::vec4> read_weights(const GltfSource& source, int accessor, const std::string& what) {
    return as_vectors<glm::vec4>(read_floats(source, accessor, 4, kAdmitFloat | kAdmitNormalizedUnsigned, 0, what));
}

std::vector<glm::mat4> read_mat4s(const GltfSource& source, int accessor, const std::string& what) {
    const auto floats = read_floats(source, accessor, 16, kAdmitFloat, 0, what);
    std::vector<glm::mat4> out(floats.size() / 16);
    for (size_t i = 0; i < out.size(); ++i) {
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) out[i][c][r] = floats[16 * i + size_t(4 * c + r)];  // column-major
        }
    }
    return out;
}

std::vector<glm::vec4> read_colors(const GltfSource& source, int accessor, const std::string& what) {
    const size_t components = get_accessor(source, accessor, what).type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
    const auto floats = read_floats(source, accessor, components, kAdmitFloat | kAdmitNormalizedUnsigned, 0, what);
    std::vector<glm::vec4> out(floats.size() / components, glm::vec4(1.0f));
    for (size_t i = 0; i < out.size(); ++i) {
        for (size_t c = 0; c < components; ++c) {
            const float v = floats[i * components + c];
            out[i][int(c)] = std::isnan(v) ? v : std::clamp(v, 0.0f, 1.0f);
        }
    }
    return out;
}

std::vector<uint32_t> read_indices(const GltfSource& source, int index, const std::string& what) {
    const tinygltf::Accessor& accessor = get_accessor(source, index, what);
    const std::string owner = "accessor " + std::to_string(index) + " (" + what + ")";
    const int ct = accessor.componentType;
    if (accessor.type != TINYGLTF_TYPE_SCALAR ||
        (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
         ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)) {
        source.fail(owner + " has type " + type_name(accessor.type) + " " + component_name(ct) +
                    "; indices must be SCALAR UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
    }
    if (accessor.sparse.isSparse) source.fail(owner + " is sparse; sparse index accessors are not supported");
    const size_t count = checked_count(source, accessor, owner);
    std::vector<uint32_t> out(count, 0u);
    if (accessor.bufferView < 0) return out;
    const size_t isize = component_size(ct);
    const auto bytes = buffer_view_bytes(source, accessor.bufferView, owner);
    const size_t view_stride = source.model.bufferViews[size_t(accessor.bufferView)].byteStride;
    const size_t stride = view_stride != 0 ? view_stride : isize;
    if (stride < isize) source.fail(owner + ": byteStride smaller than an index");
    check_fits(source, bytes, accessor.byteOffset, count, isize, stride, owner,
               "bufferView " + std::to_string(accessor.bufferView));
    const uint8_t* base = bytes.data() + accessor.byteOffset;
    for (size_t i = 0; i < count; ++i) out[i] = read_index(base + i * stride, ct);
    return out;
}

}  // namespace vplkit::scene::detail

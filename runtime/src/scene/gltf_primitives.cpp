// Primitive decoding: a primitive is decoded and validated once, however many nodes instance its
// mesh; each failure names the mesh, the primitive and the attribute.

#include "scene/gltf_primitives.hpp"

#include "scene/gltf_checks.hpp"

#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace vplkit::scene::detail {

// One glTF primitive decoded and validated once, however many nodes instance its mesh.
std::optional<PrimitiveData> decode_primitive(const GltfSource& source, int mesh_index, int primitive_index,
                                              uint32_t default_material, LoadWarnings& warnings) {
    const tinygltf::Mesh& mesh = source.model.meshes[size_t(mesh_index)];
    const tinygltf::Primitive& primitive = mesh.primitives[size_t(primitive_index)];
    const std::string label =
        "mesh " + std::to_string(mesh_index) + quoted_name(mesh.name) + " primitive " + std::to_string(primitive_index);
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES) {
        ++warnings.skipped_primitives;
        return std::nullopt;
    }
    auto attribute = [&](const char* name) {
        const auto it = primitive.attributes.find(name);
        return it == primitive.attributes.end() ? -1 : it->second;
    };
    const int position_accessor = attribute("POSITION");
    if (position_accessor < 0) {
        warnings.messages.push_back(label + " has no POSITION: skipped");
        return std::nullopt;
    }

    PrimitiveData data;
    data.positions = detail::read_positions(source, position_accessor, "POSITION of " + label);
    const size_t vertex_count = data.positions.size();
    auto check_count = [&](size_t count, const char* name) {
        if (count != vertex_count) {
            source.fail(label + ": " + name + " has " + std::to_string(count) + " elements but POSITION has " +
                        std::to_string(vertex_count));
        }
    };
    auto check_finite = [&](const float* values, size_t components, const char* name) {
        for (size_t i = 0; i < vertex_count * components; ++i) {
            if (!std::isfinite(values[i])) {
                std::ostringstream value;
                value << values[i];
                source.fail(label + ": " + name + " of vertex " + std::to_string(i / components) + " is " +
                            value.str() + " (NaN or infinite)");
            }
        }
    };
    check_finite(&data.positions[0].x, 3, "POSITION");
    if (const int a = attribute("NORMAL"); a >= 0) {
        data.normals = detail::read_normals(source, a, "NORMAL of " + label);
        check_count(data.normals.size(), "NORMAL");
        check_finite(&data.normals[0].x, 3, "NORMAL");
    }
    if (const int a = attribute("TANGENT"); a >= 0) {
        data.tangents = detail::read_tangents(source, a, "TANGENT of " + label);
        check_count(data.tangents.size(), "TANGENT");
        check_finite(&data.tangents[0].x, 4, "TANGENT");
    }
    if (const int a = attribute("TEXCOORD_0"); a >= 0) {
        data.uvs = detail::read_texcoords(source, a, "TEXCOORD_0 of " + label);
        check_count(data.uvs.size(), "TEXCOORD_0");
        check_finite(&data.uvs[0].x, 2, "TEXCOORD_0");
    }
    if (const int a = attribute("TEXCOORD_1"); a >= 0) {
        data.uvs1 = detail::read_texcoords(source, a, "TEXCOORD_1 of " + label);
        check_count(data.uvs1.size(), "TEXCOORD_1");
        check_finite(&data.uvs1[0].x, 2, "TEXCOORD_1");
    }
    if (const int a = attribute("COLOR_0"); a >= 0) {
        data.colors = detail::read_colors(source, a, "COLOR_0 of " + label);
        check_count(data.colors.size(), "COLOR_0");
        check_finite(&data.colors[0].x, 4, "COLOR_0");
    }

    for (size_t t = 0; t < primitive.targets.size(); ++t) {
        const std::string target_label = "morph target " + std::to_string(t) + " of " + label;
        const auto& attributes = primitive.targets[t];
        MorphTarget target;
        auto displacement = [&](const char* name, auto read) {
            const auto it = attributes.find(name);
            if (it == attributes.end()) return std::vector<glm::vec3>{};
            auto values = read(source, it->second, std::string(name) + " of " + target_label);
            const std::string what = "morph target " + std::to_string(t) + " " + name;
            check_count(values.size(), what.c_str());
            check_finite(&values[0].x, 3, what.c_str());
            return values;
        };
        target.positions = displacement("POSITION", detail::read_target_positions);
        target.normals = displacement("NORMAL", detail::read_target_directions);
        target.tangents = displacement("TANGENT", detail::read_target_directions);
        for (const auto& [name, accessor] : attributes) {
            if (name != "POSITION" && name != "NORMAL" && name != "TANGENT") {
                warnings.messages.push_back(target_label + ": " + name + " displacements ignored");
            }
        }
        data.targets.push_back(std::move(target));
    }
    for (int set = 0;; ++set) {
        const std::string joints_name = "JOINTS_" + std::to_string(set);
        const std::string weights_name = "WEIGHTS_" + std::to_string(set);
        const int joints = attribute(joints_name.c_str()), weights = attribute(weights_name.c_str());
        if (joints < 0 && weights < 0) break;
        if (joints < 0 || weights < 0) {
            source.fail(
                label + " has " +
                (joints < 0 ? weights_name + " without " + joints_name : joints_name + " without " + weights_name));
        }
        JointSet joint_set;
        joint_set.joints = detail::read_joints(source, joints, joints_name + " of " + label);
        joint_set.weights = detail::read_weights(source, weights, weights_name + " of " + label);
        check_count(joint_set.joints.size(), joints_name.c_str());
        check_count(joint_set.weights.size(), weights_name.c_str());
        check_finite(&joint_set.weights[0].x, 4, weights_name.c_str());
        data.joint_sets.push_back(std::move(joint_set));
    }

    if (primitive.indices >= 0) {
        data.indices = detail::read_indices(source, primitive.indices, "indices of " + label);
        for (size_t i = 0; i < data.indices.size(); ++i) {
            if (data.indices[i] >= vertex_count) {
                source.fail(label + ": index " + std::to_string(i) + " is " + std::to_string(data.indices[i]) +
                            ", but the primitive has " + std::to_string(vertex_count) + " vertices");
            }
        }
    } else {
        data.indices.resize(vertex_count);
        for (size_t i = 0; i < vertex_count; ++i) data.indices[i] = uint32_t(i);
    }
    if (data.indices.size() % 3 != 0) {
        source.fail(label + ": " + std::to_string(data.indices.size()) +
                    (primitive.indices >= 0 ? " indices" : " vertices") + " do not make whole triangles");
    }

    if (primitive.material >= 0) {
        check_index(source, primitive.material, source.model.materials, "material", label);
        data.material = uint32_t(primitive.material);
    } else {
        data.material = default_material;
    }
    return data;
}

}  // namespace vplkit::scene::detail

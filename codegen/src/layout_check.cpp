#include "layout_check.hpp"

#include <algorithm>

#include "cpp_names.hpp"
#include "error.hpp"

namespace vplkit::codegen {

namespace {

// The first difference between two layouts of one struct, in words; nullopt if equal.
std::optional<std::string> first_difference(const StructLayout& a, const StructLayout& b) {
    const size_t common = std::min(a.members.size(), b.members.size());
    for (size_t i = 0; i < common; ++i) {
        const Member& x = a.members[i];
        const Member& y = b.members[i];
        if (x.name != y.name) {
            return "member " + std::to_string(i) + " is '" + x.name + "' vs '" + y.name + "'";
        }
        if (x.offset != y.offset) {
            return "member '" + x.name + "' at offset " + std::to_string(x.offset) + " vs " + std::to_string(y.offset);
        }
        if (!(x.type == y.type)) {
            return "member '" + x.name + "' is " + describe_type(x.type) + " vs " + describe_type(y.type);
        }
    }
    if (a.members.size() > common) return "member '" + a.members[common].name + "' only in the first";
    if (b.members.size() > common) return "member '" + b.members[common].name + "' only in the second";
    return std::nullopt;
}

std::string between(const std::string& first, const std::string& second) {
    if (first == second) {
        return "has two layouts in shader '" + first +
               "' (is it used in blocks with different layouts, e.g. std140 and std430?)";
    }
    return "differs between shader '" + first + "' and shader '" + second + "'";
}

void check_struct_names(const StructLayout& s) {
    if (!is_identifier(s.name) || is_cpp_keyword(s.name) || is_builtin_type_name(s.name)) {
        throw Error("shader '" + s.shader + "': struct name '" + s.name +
                    "' cannot be used in C++ (a keyword, or a name types.hpp defines itself); rename it");
    }
    std::set<std::string> names;
    for (const Member& m : s.members) {
        const std::string id = cpp_identifier(m.name);
        // Generated names that live in the struct next to the members.
        for (const std::string& taken : {id, "k" + camel_case(m.name) + "Offset", "k" + camel_case(m.name) + "Stride",
                                         camel_case(m.name) + "Element"}) {
            if (!names.insert(taken).second) {
                throw Error("shader '" + s.shader + "': struct '" + s.name + "' member '" + m.name +
                            "' clashes with another member's C++ name '" + taken + "'");
            }
        }
        if (m.name.starts_with("_pad") || m.name == "kMembers") {
            throw Error("shader '" + s.shader + "': struct '" + s.name + "' member '" + m.name +
                        "' clashes with a name codegen generates (_pad*, kMembers); rename it");
        }
    }
}

// Dependency order (contained structs first), ties broken by name: the output must not
// depend on the order the shaders were given in.
std::vector<std::string> dependency_order(const std::map<std::string, StructLayout>& layouts) {
    std::map<std::string, std::set<std::string>> deps;
    std::map<std::string, std::set<std::string>> users;
    for (const auto& [name, layout] : layouts) {
        deps[name];
        for (const Member& m : layout.members) {
            if (m.type.kind == MemberType::Kind::Struct) {
                deps[name].insert(m.type.struct_name);
                users[m.type.struct_name].insert(name);
            }
        }
    }
    std::set<std::string> ready;
    for (const auto& [name, d] : deps) {
        if (d.empty()) ready.insert(name);
    }
    std::vector<std::string> order;
    while (!ready.empty()) {
        const std::string name = *ready.begin();
        ready.erase(ready.begin());
        order.push_back(name);
        for (const std::string& user : users[name]) {
            deps[user].erase(name);
            if (deps[user].empty()) ready.insert(user);
        }
    }
    if (order.size() != layouts.size()) throw Error("structs contain each other (a cycle); cannot order them");
    return order;
}

}  // namespace

const ResolvedStruct& TypeTable::get(const std::string& name) const {
    return structs_.at(index_.at(name));
}

CppType TypeTable::cpp_type(const MemberType& t, size_t skip_dims, const std::string& where) const {
    CppType c;
    const uint32_t s = scalar_size(t.scalar);
    switch (t.kind) {
        case MemberType::Kind::Scalar:
            c = {scalar_cpp(t.scalar), "", s, s};
            break;
        case MemberType::Kind::Vector:
            c = {vector_cpp(t.scalar, t.rows), "", s * t.rows, s};
            break;
        case MemberType::Kind::Matrix:
            if (t.matrix_stride < s * t.rows || t.matrix_stride % s != 0) {
                throw Error(where + ": matrix column stride " + std::to_string(t.matrix_stride) +
                            " cannot hold its columns");
            }
            c = {matrix_cpp(t.scalar, t.columns, t.rows, t.matrix_stride), "", t.columns * t.matrix_stride, s};
            break;
        case MemberType::Kind::Struct: {
            const ResolvedStruct& r = get(t.struct_name);
            c = {r.name, "", r.size, r.align};
            break;
        }
    }
    // Wrap dimensions from the innermost out; a stride wider than the element gets an
    // explicitly padded element type, a narrower one cannot be expressed in C++.
    for (size_t k = t.dims.size(); k-- > skip_dims;) {
        const ArrayDim& d = t.dims[k];
        if (d.stride < c.size || d.stride % c.align != 0) {
            throw Error(where + ": array stride " + std::to_string(d.stride) + " does not fit its C++ element type " +
                        c.type + c.suffix + " (" + std::to_string(c.size) + " bytes, aligned to " +
                        std::to_string(c.align) + ")");
        }
        if (d.stride != c.size) {
            c.type = "padded<" + c.type + c.suffix + ", " + std::to_string(d.stride) + ">";
            c.suffix.clear();
        }
        c.suffix = "[" + std::to_string(d.count) + "]" + c.suffix;
        c.size = d.stride * d.count;
    }
    return c;
}

CppType TypeTable::runtime_element(const MemberType& t, const std::string& where) const {
    CppType c = cpp_type(t, 1, where);
    const uint32_t stride = t.dims.front().stride;
    if (stride < c.size || stride % c.align != 0) {
        throw Error(where + ": runtime array stride " + std::to_string(stride) + " does not fit its C++ element type " +
                    c.type + c.suffix + " (" + std::to_string(c.size) + " bytes)");
    }
    if (stride != c.size) {
        c.type = "padded<" + c.type + c.suffix + ", " + std::to_string(stride) + ">";
        c.suffix.clear();
        c.size = stride;
    }
    return c;
}

TypeTable build_type_table(const std::vector<ShaderModel>& shaders) {
    // 1. Merge: one layout per name, every copy must agree.
    std::map<std::string, StructLayout> layouts;
    std::map<std::string, std::set<std::string>> users;
    for (const ShaderModel& shader : shaders) {
        for (const StructLayout& s : shader.structs) {
            auto [it, inserted] = layouts.emplace(s.name, s);
            if (inserted) {
                check_struct_names(s);
            } else if (auto diff = first_difference(it->second, s)) {
                throw Error("struct '" + s.name + "' " + between(it->second.shader, s.shader) + ": " + *diff);
            }
            users[s.name].insert(shader.name);
        }
    }
    std::map<std::string, ArrayUse> array_uses;
    for (const ShaderModel& shader : shaders) {
        for (const ArrayUse& use : shader.array_uses) {
            auto [it, inserted] = array_uses.emplace(use.struct_name, use);
            if (!inserted && it->second.stride != use.stride) {
                throw Error("struct '" + use.struct_name + "' " + between(it->second.shader, use.shader) +
                            ": array stride " + std::to_string(it->second.stride) + " (" + it->second.where + ") vs " +
                            std::to_string(use.stride) + " (" + use.where + ")");
            }
        }
    }

    // 2. Resolve C++ sizes in dependency order (a struct's size needs its members' sizes).
    TypeTable table;
    for (const std::string& name : dependency_order(layouts)) {
        const StructLayout& layout = layouts.at(name);
        ResolvedStruct r;
        r.name = name;
        r.members = layout.members;
        r.shaders.assign(users[name].begin(), users[name].end());
        const std::string origin = "shader '" + layout.shader + "': struct '" + name + "'";

        uint32_t end = 0;
        std::string previous;
        for (const Member& m : r.members) {
            const std::string where = origin + " member '" + m.name + "'";
            const bool runtime = m.type.is_runtime_array();
            const CppType c = runtime ? table.runtime_element(m.type, where) : table.cpp_type(m.type, 0, where);
            if (m.offset < end) {
                throw Error(where + " at offset " + std::to_string(m.offset) + " overlaps member '" + previous +
                            "', which ends at " + std::to_string(end) +
                            " in C++ (a struct member padded to its "
                            "array stride elsewhere, or 64-bit members under scalar layout?)");
            }
            if (m.offset % c.align != 0) {
                throw Error(where + " at offset " + std::to_string(m.offset) + " is not aligned to its C++ type " +
                            c.type + " (" + std::to_string(c.align) + " bytes)");
            }
            r.align = std::max(r.align, c.align);
            end = runtime ? m.offset : m.offset + c.size;
            previous = m.name;
            if (m.type.kind == MemberType::Kind::Matrix) {
                table.matrices_.insert({m.type.scalar, m.type.columns, m.type.rows, m.type.matrix_stride});
                table.vectors_.insert({m.type.scalar, m.type.rows});
            } else if (m.type.kind == MemberType::Kind::Vector) {
                table.vectors_.insert({m.type.scalar, m.type.rows});
            }
        }
        r.size = end;
        if (auto use = array_uses.find(name); use != array_uses.end()) {
            r.array_stride = use->second.stride;
            if (use->second.stride < end || use->second.stride % r.align != 0) {
                throw Error(origin + " (" + std::to_string(end) + " bytes in C++, aligned to " +
                            std::to_string(r.align) + ") does not fit its array stride " +
                            std::to_string(use->second.stride) + " in shader '" + use->second.shader + "' (" +
                            use->second.where + ")");
            }
            r.size = use->second.stride;
        }
        if (r.runtime_array() == nullptr) {
            r.size = (r.size + r.align - 1) / r.align * r.align;  // explicit trailing padding
        } else if (r.size % r.align != 0) {
            throw Error(origin + ": the members before the runtime array end at " + std::to_string(r.size) +
                        ", which C++ cannot express for a struct aligned to " + std::to_string(r.align));
        }
        table.index_[name] = table.structs_.size();
        table.structs_.push_back(std::move(r));
    }
    return table;
}

}  // namespace vplkit::codegen

// vplkit-codegen: SPIR-V modules -> C++ headers.
//
//   vplkit-codegen --namespace NS --header-dir DIR --out ROOT
//                  --shader NAME FILE.spv [--shader NAME FILE.spv ...]
//
// writes ROOT/DIR/types.hpp and ROOT/DIR/NAME.hpp per shader. Every check runs and every
// header text is built before the first file is written: an error leaves no partial output.
#include <cstdio>
#include <exception>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cpp_names.hpp"
#include "emit.hpp"
#include "error.hpp"
#include "layout_check.hpp"
#include "output.hpp"
#include "reflect.hpp"

namespace vc = vplkit::codegen;

namespace {

constexpr const char* kUsage =
    "usage: vplkit-codegen --namespace NS --header-dir DIR --out ROOT --shader NAME FILE.spv [--shader NAME FILE.spv "
    "...]";

struct Options {
    std::string cpp_namespace;
    std::string header_dir;
    std::string out_root;
    std::vector<std::pair<std::string, std::string>> shaders;  // name, .spv path
};

Options parse_arguments(int argc, char** argv) {
    Options o;
    auto value = [&](int& i) -> std::string {
        if (i + 1 >= argc) throw vc::Error(std::string(argv[i]) + " needs a value; " + kUsage);
        return argv[++i];
    };
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--namespace") {
            o.cpp_namespace = value(i);
        } else if (arg == "--header-dir") {
            o.header_dir = value(i);
        } else if (arg == "--out") {
            o.out_root = value(i);
        } else if (arg == "--shader") {
            std::string name = value(i);
            o.shaders.emplace_back(name, value(i));
        } else {
            throw vc::Error("unknown argument '" + arg + "'; " + kUsage);
        }
    }
    if (o.cpp_namespace.empty() || o.header_dir.empty() || o.out_root.empty() || o.shaders.empty()) {
        throw vc::Error(kUsage);
    }
    // NS may be nested (vplkit::shaders): each part must be a plain identifier.
    size_t start = 0;
    while (true) {
        const size_t end = o.cpp_namespace.find("::", start);
        const std::string part =
            o.cpp_namespace.substr(start, end == std::string::npos ? std::string::npos : end - start);
        if (!vc::is_identifier(part) || vc::is_cpp_keyword(part)) {
            throw vc::Error("namespace '" + o.cpp_namespace + "' is not a C++ namespace name");
        }
        if (end == std::string::npos) break;
        start = end + 2;
    }
    std::set<std::string> names;
    for (const auto& [name, path] : o.shaders) {
        if (!vc::is_identifier(name) || vc::is_cpp_keyword(name)) {
            throw vc::Error("shader name '" + name +
                            "' is not a C++ identifier (it becomes a namespace); rename the file");
        }
        if (name == "types")
            throw vc::Error("a shader cannot be named 'types' (types.hpp is the shared struct header)");
        if (!names.insert(name).second) throw vc::Error("shader name '" + name + "' is given twice");
    }
    return o;
}

int run(int argc, char** argv) {
    const Options options = parse_arguments(argc, argv);
    std::vector<vc::ShaderModel> shaders;
    for (const auto& [name, path] : options.shaders) {
        shaders.push_back(vc::reflect_shader(name, vc::read_spirv_file(path)));
    }
    const vc::TypeTable types = vc::build_type_table(shaders);
    for (const vc::ShaderModel& s : shaders) {
        if (types.contains(s.name) || vc::is_builtin_type_name(s.name)) {
            throw vc::Error("shader '" + s.name +
                            "' has the name of a struct in types.hpp; rename the shader or the struct");
        }
    }

    const vc::EmitOptions emit{options.cpp_namespace};
    const std::filesystem::path dir = std::filesystem::path(options.out_root) / options.header_dir;
    std::map<std::filesystem::path, std::string> files;
    files[dir / "types.hpp"] = vc::emit_types_header(types, emit);
    for (const vc::ShaderModel& s : shaders) files[dir / (s.name + ".hpp")] = vc::emit_shader_header(s, emit);
    vc::write_changed_files(files);
    return 0;
}

// Errors are one line: build logs and tests match on it.
void report(const std::string& prefix, std::string message) {
    for (char& c : message) {
        if (c == '\n' || c == '\r') c = ' ';
    }
    std::fprintf(stderr, "vplkit-codegen: %s%s\n", prefix.c_str(), message.c_str());
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const vc::Error& e) {
        report("", e.what());
    } catch (const std::exception& e) {
        report("internal error: ", e.what());
    }
    return 1;
}

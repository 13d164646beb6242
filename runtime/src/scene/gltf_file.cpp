// tinygltf parses the file and loads its buffers; its error texts are turned into one line that
// names the file and says the problem in vplkit's words.

#include "scene/gltf_file.hpp"

#include "scene/gltf_checks.hpp"
#include "vplkit/error.hpp"

#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>

namespace vplkit::scene::detail {
namespace {

const std::set<std::string> kSupportedExtensions = {kLightsExtension, kEmissiveStrengthExtension,
                                                    kTextureTransformExtension, kQuantizationExtension};

// tinygltf's error text, which may span lines, as one line ("first; second").
std::string one_line(const std::string& text) {
    std::string out;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        while (!line.empty() && (line.back() == ' ' || line.back() == '\r')) line.pop_back();
        if (line.empty()) continue;
        if (!out.empty()) out += "; ";
        out += line;
    }
    return out;
}

// tinygltf reports a missing or short buffer file as "File not found : <uri>" or
// "File size mismatch : <path>, requestedBytes N, but got M": say it in vplkit's words, with the
// full path.
std::optional<std::string> buffer_problem(const std::string& why, const std::filesystem::path& base_dir) {
    constexpr std::string_view kNotFound = "File not found : ";
    constexpr std::string_view kMismatch = "File size mismatch : ";
    if (why.rfind(kNotFound, 0) == 0) {
        const std::string uri = why.substr(kNotFound.size(), why.find(';') - kNotFound.size());
        return "buffer file " + (base_dir / uri).lexically_normal().string() + " not found";
    }
    if (why.rfind(kMismatch, 0) == 0) {
        const size_t comma = why.find(", requestedBytes ");
        const size_t got = why.find(", but got ");
        if (comma != std::string::npos && got != std::string::npos) {
            const std::string buffer = why.substr(kMismatch.size(), comma - kMismatch.size());
            const std::string requested = why.substr(comma + 17, got - comma - 17);
            const std::string actual = why.substr(got + 10, why.find(';', got) - got - 10);
            return "buffer file " + buffer + " has " + actual + " bytes, but the glTF declares " + requested +
                   " (truncated or the wrong file)";
        }
    }
    return std::nullopt;
}

// tinygltf joins every buffer and image URI to the glTF file's folder, an absolute-path reference
// too ("dir" + "/" + "/abs/b.bin": not found although /abs/b.bin exists). RFC 3986 resolves a
// reference that starts with '/' to that path alone; `base_dir` is the folder tinygltf joins
// (everything before the file name's last separator, as its GetBaseDir takes it).
std::string expand_uri_path(const std::string& joined, void* base_dir) {
    const std::string& base = *static_cast<const std::string*>(base_dir);
    const std::string absolute_join = base + "//";
    if (!base.empty() && joined.rfind(absolute_join, 0) == 0) {
        return tinygltf::ExpandFilePath(joined.substr(base.size() + 1), nullptr);
    }
    return tinygltf::ExpandFilePath(joined, nullptr);
}

bool is_glb(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    char magic[4] = {};
    file.read(magic, 4);
    return file.gcount() == 4 && std::string_view(magic, 4) == "glTF";
}

}  // namespace

tinygltf::Model read_gltf_file(const std::filesystem::path& path, CapturedImages& captured, std::string& warn) {
    const std::string file = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error(file + ": file not found");
    if (std::filesystem::is_directory(path, ec)) throw Error(file + ": is a directory, not a glTF file");

    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&capture_image_bytes, &captured);
    const size_t separator = file.find_last_of("/\\");
    std::string base_dir = separator == std::string::npos ? std::string() : file.substr(0, separator);
    loader.SetFsCallbacks(
        {&tinygltf::FileExists, &expand_uri_path, &tinygltf::ReadWholeFile, &tinygltf::WriteWholeFile, &base_dir});
    std::string err;
    const bool ok = is_glb(path) ? loader.LoadBinaryFromFile(&model, &err, &warn, file)
                                 : loader.LoadASCIIFromFile(&model, &err, &warn, file);
    if (!ok) {
        std::string why = one_line(err.empty() ? warn : err);
        // nlohmann's "[json.exception.parse_error.101] parse error at ..." says what, not where from.
        constexpr std::string_view kJsonParse = "[json.exception.parse_error.";
        if (const size_t at = why.find(kJsonParse); at != std::string::npos) {
            const size_t end = why.find("] ", at);
            if (end != std::string::npos) why = "malformed JSON: " + why.substr(end + 2);
        }
        why = buffer_problem(why, path.parent_path()).value_or("cannot be loaded: " + why);
        throw Error(file + ": " + (why.empty() ? "cannot be loaded (tinygltf gave no reason)" : why));
    }
    return model;
}

void check_extensions(const GltfSource& source, LoadWarnings& warnings) {
    for (const std::string& name : source.model.extensionsRequired) {
        if (!kSupportedExtensions.count(name)) {
            std::string supported;
            for (const std::string& e : kSupportedExtensions) supported += (supported.empty() ? "" : ", ") + e;
            source.fail("the file requires extension " + name +
                        ", which vplkit does not support (supported: " + supported + ")");
        }
    }
    for (const std::string& name : source.model.extensionsUsed) {
        if (!kSupportedExtensions.count(name)) {
            warnings.messages.push_back("extension " + name + " ignored (not required by the file)");
        }
    }
}

}  // namespace vplkit::scene::detail

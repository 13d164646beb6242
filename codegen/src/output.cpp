#include "output.hpp"

#include <fstream>
#include <iterator>
#include <system_error>

#include "error.hpp"

namespace vplkit::codegen {

namespace {

bool has_content(const std::filesystem::path& path, const std::string& text) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    const std::string current((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return current == text;
}

}  // namespace

void write_changed_files(const std::map<std::filesystem::path, std::string>& files) {
    for (const auto& [path, text] : files) {
        if (has_content(path, text)) continue;
        std::error_code ec;
        std::filesystem::create_directories(path.parent_path(), ec);
        if (ec) throw Error("cannot create directory '" + path.parent_path().string() + "': " + ec.message());
        std::filesystem::path temp = path;
        temp += ".tmp";
        {
            std::ofstream out(temp, std::ios::binary | std::ios::trunc);
            out << text;
            out.close();
            if (!out) {
                std::filesystem::remove(temp, ec);
                throw Error("cannot write '" + temp.string() + "'");
            }
        }
        std::filesystem::rename(temp, path, ec);
        if (ec) {
            std::filesystem::remove(temp, ec);
            throw Error("cannot write '" + path.string() + "': " + ec.message());
        }
    }
}

}  // namespace vplkit::codegen

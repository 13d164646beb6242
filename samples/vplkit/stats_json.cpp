#include "stats_json.hpp"

#include "vplkit/error.hpp"

#include <cmath>
#include <fstream>
#include <system_error>

#include <unistd.h>

namespace vplkit::cli {

nlohmann::ordered_json json_number(double value) {
    if (!std::isfinite(value)) return nullptr;
    return value;
}

std::string json_text(const nlohmann::ordered_json& document) {
    // nlohmann writes a non-finite float as null too; json_number makes it explicit where the
    // values are made, so the file does not rely on that.
    return document.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

void write_json_file(const std::filesystem::path& path, const nlohmann::ordered_json& document) {
    const std::string text = json_text(document);
    const std::filesystem::path partial = path.string() + ".tmp" + std::to_string(::getpid());
    {
        std::ofstream out(partial, std::ios::binary);
        out << text;
        out.close();
        if (!out) {
            std::error_code ignored;
            std::filesystem::remove(partial, ignored);
            throw Error("could not write " + path.string() + " (is the folder there and writable?)");
        }
    }
    std::error_code error;
    std::filesystem::rename(partial, path, error);
    if (error) {
        std::filesystem::remove(partial, error);
        throw Error("could not write " + path.string() + ": " + error.message());
    }
}

}  // namespace vplkit::cli

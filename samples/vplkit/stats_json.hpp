#pragma once
// JSON files through nlohmann-json: numbers that are not finite (NaN, infinity) are written as
// null, since JSON has no such numbers; strings are escaped by the library (control characters
// as \u00XX), and bytes that are not UTF-8 (a file name can hold any) are replaced by U+FFFD
// rather than failing. Files are written to a temporary name and renamed into place, so a
// failure never leaves a partial file.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace vplkit::cli {

// `value`, or null when it is NaN or infinite.
nlohmann::ordered_json json_number(double value);

// The document as written: two-space indents, a newline at the end.
std::string json_text(const nlohmann::ordered_json& document);

// Throws vplkit::Error naming `path` when it cannot be written (nothing is left at `path` then).
void write_json_file(const std::filesystem::path& path, const nlohmann::ordered_json& document);

}  // namespace vplkit::cli

// Writing the generated files: all or nothing, and only when the text changed.
#pragma once

#include <filesystem>
#include <map>
#include <string>

namespace vplkit::codegen {

// Writes every file whose current content differs from its text. Unchanged files keep their
// timestamps, so a shader edit that leaves a header's text alone rebuilds nothing.
// Each file is written to a temporary name and renamed, so a reader never sees half a file.
void write_changed_files(const std::map<std::filesystem::path, std::string>& files);

}  // namespace vplkit::codegen

#pragma once
// Layered OpenEXR files (OpenEXR 3): one file holding the frame's parts as named layers, channel
// names "<layer>.<channel>" ("beauty.R", "depth.Z"), as compositing tools read them. Written to a
// temporary name in the same folder, read back to check it is complete, then renamed into place:
// a failure leaves no partial file.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace vplkit::cli {

struct ExrLayer {
    std::string name;                   // "beauty"
    std::vector<std::string> channels;  // "R", "G", "B"; "Z"; ...
    // width * height * channels.size() floats, a pixel's channels together, rows top to bottom.
    std::span<const float> values;
    // Stored as 16-bit floats (3 significant digits, at most 65504): for bounded data such as
    // albedo and normals. Radiance and depth stay 32-bit (a sun-lit pixel can exceed 65504).
    bool half = false;
};

// Throws vplkit::Error naming `path` for a layer of the wrong size or a file that could not be
// written. `comment` goes into the file's "comments" attribute (what the layers mean).
void write_exr(const std::filesystem::path& path, uint32_t width, uint32_t height, std::span<const ExrLayer> layers,
               const std::string& comment = "");

}  // namespace vplkit::cli

#pragma once
// Image files: PNG (8-bit, what people look at) and PFM (linear float RGB, what error metrics
// and ground truth use; read by every tool). Writes go to a temporary file in the same folder
// that is renamed into place, so a failure never leaves a partial file at `path`.

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace vplkit {

// `rgba` holds width * height * 4 bytes, rows top to bottom.
void write_png(const std::filesystem::path& path, uint32_t width, uint32_t height, std::span<const uint8_t> rgba);

// `rgb` holds width * height * 3 floats, rows top to bottom (the file stores them bottom to top,
// little-endian, as PFM specifies).
void write_pfm(const std::filesystem::path& path, uint32_t width, uint32_t height, std::span<const float> rgb);

struct PfmImage {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<float> rgb;  // rows top to bottom
};
// Reads colour ("PF") and greyscale ("Pf", expanded to RGB) files of either byte order.
PfmImage read_pfm(const std::filesystem::path& path);

}  // namespace vplkit

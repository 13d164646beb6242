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

struct PngImage {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba;  // width * height * 4 bytes, rows top to bottom
};
// Reads any PNG as 8-bit RGBA: grey is expanded to RGB, a missing alpha channel reads as 255,
// palettes are resolved, and 16-bit files are reduced to their 8 high bits (stb_image's rule).
// The bytes are the file's codes as stored, sRGB-encoded for the PNGs vplkit writes; nothing
// is linearized. Throws vplkit::Error naming the file when it cannot be opened, does not start
// with the PNG signature, or cannot be decoded (truncated, corrupt).
PngImage read_png(const std::filesystem::path& path);

}  // namespace vplkit

#include "vplkit/image_io.hpp"

#include "vplkit/error.hpp"

#define STB_IMAGE_WRITE_STATIC  // private copy: tinygltf's library may carry its own
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

// The runtime's one copy of the decoder, private for the same reason, and PNG only: read_png
// promises to refuse anything else, and the other formats' decoders would be dead code.
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STBI_NO_STDIO  // read_png opens the file itself, to name the failure
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <memory>
#include <string>
#include <unistd.h>

namespace vplkit {

namespace {

// Writes through `write_file(temporary path)` and renames the result into place.
void write_atomically(const std::filesystem::path& path, const std::function<bool(const std::string&)>& write_file) {
    const std::filesystem::path temporary = path.string() + ".tmp" + std::to_string(::getpid());
    if (!write_file(temporary.string())) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw Error("could not write " + path.string() + " (is the folder there and writable?)");
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::filesystem::remove(temporary, error);
        throw Error("could not write " + path.string() + ": " + error.message());
    }
}

void check_size(const char* what, const std::filesystem::path& path, uint32_t width, uint32_t height, size_t got,
                size_t per_pixel) {
    if (width == 0 || height == 0 || got != size_t(width) * height * per_pixel) {
        throw Error(std::string(what) + " " + path.string() + ": " + std::to_string(width) + "x" +
                    std::to_string(height) + " image needs " + std::to_string(size_t(width) * height * per_pixel) +
                    " values, got " + std::to_string(got));
    }
}

}  // namespace

void write_png(const std::filesystem::path& path, uint32_t width, uint32_t height, std::span<const uint8_t> rgba) {
    check_size("PNG", path, width, height, rgba.size(), 4);
    write_atomically(path, [&](const std::string& file) {
        return stbi_write_png(file.c_str(), int(width), int(height), 4, rgba.data(), int(width * 4)) != 0;
    });
}

void write_pfm(const std::filesystem::path& path, uint32_t width, uint32_t height, std::span<const float> rgb) {
    check_size("PFM", path, width, height, rgb.size(), 3);
    static_assert(std::endian::native == std::endian::little, "PFM files are written little-endian (scale -1)");
    write_atomically(path, [&](const std::string& file) {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out << "PF\n" << width << ' ' << height << "\n-1.0\n";
        for (uint32_t row = height; row-- > 0;) {  // PFM stores the bottom row first
            out.write(reinterpret_cast<const char*>(rgb.data() + size_t(row) * width * 3),
                      std::streamsize(width) * 3 * 4);
        }
        return bool(out.flush());
    });
}

PfmImage read_pfm(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw Error("cannot open " + path.string());
    }
    std::string magic;
    double scale = 0.0;
    PfmImage image;
    in >> magic >> image.width >> image.height >> scale;
    if (!in || (magic != "PF" && magic != "Pf") || image.width == 0 || image.height == 0 || scale == 0.0 ||
        image.width > 65536 || image.height > 65536) {
        throw Error(path.string() + " is not a PFM file (bad header)");
    }
    in.get();  // the single whitespace byte after the scale
    const uint32_t channels = magic == "PF" ? 3 : 1;
    std::vector<float> file_order(size_t(image.width) * image.height * channels);
    in.read(reinterpret_cast<char*>(file_order.data()), std::streamsize(file_order.size() * 4));
    if (in.gcount() != std::streamsize(file_order.size() * 4)) {
        throw Error(path.string() + " is truncated: expected " + std::to_string(file_order.size() * 4) +
                    " bytes of pixels");
    }
    const bool big_endian = scale > 0.0;
    image.rgb.resize(size_t(image.width) * image.height * 3);
    for (uint32_t row = 0; row < image.height; ++row) {
        const uint32_t file_row = image.height - 1 - row;
        for (uint32_t x = 0; x < image.width; ++x) {
            for (uint32_t c = 0; c < 3; ++c) {
                float v = file_order[(size_t(file_row) * image.width + x) * channels + (channels == 3 ? c : 0)];
                if (big_endian) {
                    uint32_t bits = std::bit_cast<uint32_t>(v);
                    bits = (bits >> 24) | ((bits >> 8) & 0xff00u) | ((bits << 8) & 0xff0000u) | (bits << 24);
                    v = std::bit_cast<float>(bits);
                }
                image.rgb[(size_t(row) * image.width + x) * 3 + c] = v;
            }
        }
    }
    return image;
}

PngImage read_png(const std::filesystem::path& path) {
    std::error_code ignored;
    if (std::filesystem::is_directory(path, ignored)) {
        throw Error("cannot open " + path.string() + ": it is a folder");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw Error("cannot open " + path.string());
    }
    const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) {
        throw Error("cannot read " + path.string());
    }
    static constexpr std::array<unsigned char, 8> kSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (bytes.size() < kSignature.size() || !std::equal(kSignature.begin(), kSignature.end(), bytes.begin())) {
        throw Error(path.string() + " is not a PNG file (no PNG signature)");
    }
    if (bytes.size() > size_t(INT32_MAX)) {
        throw Error(path.string() + " is too large to read (" + std::to_string(bytes.size()) + " bytes)");
    }
    int width = 0, height = 0, channels_in_file = 0;
    const std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
        stbi_load_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels_in_file, 4), stbi_image_free);
    if (!pixels || width <= 0 || height <= 0) {
        const char* reason = stbi_failure_reason();
        throw Error(path.string() + " is not a readable PNG file (" + (reason ? reason : "decoder failed") + ")");
    }
    PngImage image;
    image.width = uint32_t(width);
    image.height = uint32_t(height);
    image.rgba.assign(pixels.get(), pixels.get() + size_t(image.width) * image.height * 4);
    return image;
}

}  // namespace vplkit

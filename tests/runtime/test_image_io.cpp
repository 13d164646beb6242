// PNG and PFM files: exact round trips, and failures that name the file and leave nothing behind.

#include "vplkit/error.hpp"
#include "vplkit/image_io.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;

namespace {

fs::path temp_dir() {
    fs::path dir = fs::temp_directory_path() / ("vplkit_image_io_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir;
}

}  // namespace

TEST_CASE("PFM round trip is exact - including extreme and non-finite values") {
    const uint32_t width = 5, height = 3;
    std::vector<float> rgb(width * height * 3);
    for (size_t i = 0; i < rgb.size(); ++i) {
        rgb[i] = float(i) * 0.37f - 2.0f;
    }
    rgb[1] = 1e-30f;
    rgb[2] = 3e38f;
    rgb[4] = std::numeric_limits<float>::infinity();
    const fs::path path = temp_dir() / "roundtrip.pfm";
    vplkit::write_pfm(path, width, height, rgb);
    vplkit::PfmImage back = vplkit::read_pfm(path);
    CHECK(back.width == width);
    CHECK(back.height == height);
    CHECK(back.rgb == rgb);  // top row first in memory, whatever the file order
}

TEST_CASE("PFM files written by other tools: big-endian and greyscale") {
    const fs::path path = temp_dir() / "other.pfm";
    {
        std::ofstream out(path, std::ios::binary);
        out << "Pf\n2 2\n1.0\n";  // greyscale, big-endian (positive scale), bottom row first
        const uint32_t values[4] = {0x3f800000u, 0x40000000u, 0x40400000u, 0x40800000u};  // 1, 2, 3, 4
        for (uint32_t v : values) {
            const unsigned char bytes[4] = {uint8_t(v >> 24), uint8_t(v >> 16), uint8_t(v >> 8), uint8_t(v)};
            out.write(reinterpret_cast<const char*>(bytes), 4);
        }
    }
    vplkit::PfmImage image = vplkit::read_pfm(path);
    // Top row (file's second row) is 3, 4; bottom row 1, 2; each grey value in all three channels.
    const std::vector<float> expected = {3, 3, 3, 4, 4, 4, 1, 1, 1, 2, 2, 2};
    CHECK(image.rgb == expected);
}

TEST_CASE("PFM: truncated and non-PFM files are refused by name") {
    const fs::path dir = temp_dir();
    {
        std::ofstream out(dir / "short.pfm", std::ios::binary);
        out << "PF\n4 4\n-1.0\n"
            << "abc";
    }
    CHECK_THROWS_WITH_AS(vplkit::read_pfm(dir / "short.pfm"), doctest::Contains("short.pfm is truncated"),
                         vplkit::Error);
    {
        std::ofstream out(dir / "text.pfm");
        out << "hello";
    }
    CHECK_THROWS_WITH_AS(vplkit::read_pfm(dir / "text.pfm"), doctest::Contains("text.pfm is not a PFM file"),
                         vplkit::Error);
}

TEST_CASE("PNG round trip is exact: read_png gives back the bytes write_png was given") {
    const uint32_t width = 7, height = 4;
    std::vector<uint8_t> rgba(width * height * 4);
    for (size_t i = 0; i < rgba.size(); ++i) {
        rgba[i] = uint8_t(i * 37 + 11);  // every channel, alpha included, takes many values
    }
    const fs::path path = temp_dir() / "roundtrip.png";
    vplkit::write_png(path, width, height, rgba);
    const vplkit::PngImage back = vplkit::read_png(path);
    CHECK(back.width == width);
    CHECK(back.height == height);
    CHECK(back.rgba == rgba);  // top row first, alpha as written
}

TEST_CASE("PNG: missing, non-PNG and truncated files are refused by name") {
    const fs::path dir = temp_dir();
    const std::string missing = "cannot open " + (dir / "nosuch.png").string();
    CHECK_THROWS_WITH_AS(vplkit::read_png(dir / "nosuch.png"), doctest::Contains(missing.c_str()), vplkit::Error);
    {
        std::ofstream out(dir / "text.png");
        out << "hello";
    }
    CHECK_THROWS_WITH_AS(vplkit::read_png(dir / "text.png"), doctest::Contains("text.png is not a PNG file"),
                         vplkit::Error);
    const std::vector<float> rgb(2 * 2 * 3, 0.5f);
    vplkit::write_pfm(dir / "image.pfm", 2, 2, rgb);  // a real image, just not a PNG
    CHECK_THROWS_WITH_AS(vplkit::read_png(dir / "image.pfm"), doctest::Contains("image.pfm is not a PNG file"),
                         vplkit::Error);
    const std::string folder = "cannot open " + dir.string() + ": it is a folder";
    CHECK_THROWS_WITH_AS(vplkit::read_png(dir), doctest::Contains(folder.c_str()), vplkit::Error);

    // The right signature, then the file stops half way: the decoder's failure, named.
    const std::vector<uint8_t> rgba(16 * 16 * 4, 200);
    vplkit::write_png(dir / "whole.png", 16, 16, rgba);
    std::ifstream in(dir / "whole.png", std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    REQUIRE(bytes.size() > 40);
    {
        std::ofstream out(dir / "short.png", std::ios::binary);
        out.write(bytes.data(), std::streamsize(bytes.size() / 2));
    }
    CHECK_THROWS_WITH_AS(vplkit::read_png(dir / "short.png"), doctest::Contains("short.png is not a readable PNG file"),
                         vplkit::Error);
}

TEST_CASE("image files: a folder that does not exist gives an error and no file") {
    const fs::path path = temp_dir() / "no_such_folder" / "out.png";
    std::vector<uint8_t> rgba(4, 255);
    CHECK_THROWS_WITH_AS(vplkit::write_png(path, 1, 1, rgba), doctest::Contains("could not write"), vplkit::Error);
    CHECK_FALSE(fs::exists(path));
    std::vector<float> rgb(2, 0.0f);  // wrong size for 1x1
    CHECK_THROWS_WITH_AS(vplkit::write_pfm(temp_dir() / "bad.pfm", 1, 1, rgb), doctest::Contains("needs 3 values"),
                         vplkit::Error);
    CHECK_FALSE(fs::exists(temp_dir() / "bad.pfm"));
}

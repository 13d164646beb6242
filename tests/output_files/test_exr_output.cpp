// write_exr (samples/vplkit/exr_output.hpp) read back through the OpenEXR library: layer and
// channel names, 32-bit values bit for bit (infinity too), 16-bit ones to half precision, rows top
// to bottom; a refused or failed write leaves no file.

#include "exr_output.hpp"
#include "test_files.hpp"

#include "vplkit/error.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace {

using vplkit::cli::ExrLayer;

// One channel of `file` as floats, rows top to bottom.
std::vector<float> read_channel(Imf::InputFile& file, const std::string& name) {
    const Imath::Box2i window = file.header().dataWindow();
    const size_t width = size_t(window.max.x - window.min.x + 1), height = size_t(window.max.y - window.min.y + 1);
    std::vector<float> values(width * height);
    Imf::FrameBuffer frame;
    frame.insert(name,
                 Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data()), sizeof(float), sizeof(float) * width));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return values;
}

}  // namespace

TEST_CASE("write_exr stores 32-bit and 16-bit layers that read back in place") {
    vplkit::test::ScratchFolder folder("exr-layers");
    const uint32_t width = 3, height = 2;
    const float inf = std::numeric_limits<float>::infinity();
    // RGB, a pixel's channels together, rows top to bottom: values a half could not hold.
    const std::vector<float> light = {1e6f, 1e-20f, 0.1f, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
    const std::vector<float> depth = {1.5f, 2.25f, inf, 4, 5, 6};
    const std::vector<float> normal = {0, 0, 1, 0.6f, 0.8f, 0, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0.3333f, 0.6667f, 0.6667f};
    const std::vector<ExrLayer> layers = {{"beauty", {"R", "G", "B"}, light, false},
                                          {"depth", {"Z"}, depth, false},
                                          {"normal", {"X", "Y", "Z"}, normal, true}};
    const auto path = folder.path / "layers.exr";
    vplkit::cli::write_exr(path, width, height, layers, "a test");
    CHECK(folder.names() == std::vector<std::string>{"layers.exr"});

    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    CHECK(window.max.x - window.min.x + 1 == int(width));
    CHECK(window.max.y - window.min.y + 1 == int(height));
    const Imf::ChannelList& channels = file.header().channels();
    for (const char* name : {"beauty.R", "beauty.G", "beauty.B", "depth.Z", "normal.X", "normal.Y", "normal.Z"}) {
        CAPTURE(name);
        REQUIRE(channels.findChannel(name) != nullptr);
        const bool half = std::string(name).starts_with("normal");
        CHECK(channels.findChannel(name)->type == (half ? Imf::HALF : Imf::FLOAT));
    }
    int count = 0;
    for (auto it = channels.begin(); it != channels.end(); ++it) ++count;
    CHECK(count == 7);

    const char* rgb[] = {"beauty.R", "beauty.G", "beauty.B"};
    for (int c = 0; c < 3; ++c) {
        const std::vector<float> values = read_channel(file, rgb[c]);
        for (size_t i = 0; i < values.size(); ++i) CHECK(values[i] == light[i * 3 + c]);  // bit for bit
    }
    CHECK(read_channel(file, "depth.Z") == depth);  // infinity included
    const char* xyz[] = {"normal.X", "normal.Y", "normal.Z"};
    for (int c = 0; c < 3; ++c) {
        const std::vector<float> values = read_channel(file, xyz[c]);
        for (size_t i = 0; i < values.size(); ++i) CHECK(std::abs(values[i] - normal[i * 3 + c]) <= 1e-3f);
    }
}

TEST_CASE("write_exr refuses a layer of the wrong size and writes nothing") {
    vplkit::test::ScratchFolder folder("exr-size");
    const std::vector<float> short_layer(5, 1.0f);
    const std::vector<ExrLayer> layers = {{"depth", {"Z"}, short_layer, false}};
    CHECK_THROWS_WITH_AS(vplkit::cli::write_exr(folder.path / "short.exr", 3, 2, layers),
                         doctest::Contains("layer 'depth' has 5 values"), vplkit::Error);
    CHECK(folder.names().empty());
}

TEST_CASE("write_exr that cannot put its file in place names it and leaves nothing behind") {
    vplkit::test::ScratchFolder folder("exr-unwritable");
    // A folder of that name: the rename into place fails after the whole file was written.
    std::filesystem::create_directory(folder.path / "taken.exr");
    const std::vector<float> depth(4, 1.0f);
    const std::vector<ExrLayer> layers = {{"depth", {"Z"}, depth, false}};
    const std::string message = "could not write " + (folder.path / "taken.exr").string();
    CHECK_THROWS_WITH_AS(vplkit::cli::write_exr(folder.path / "taken.exr", 2, 2, layers),
                         doctest::Contains(message.c_str()), vplkit::Error);
    CHECK(folder.names() == std::vector<std::string>{"taken.exr"});
    CHECK(std::filesystem::is_empty(folder.path / "taken.exr"));
    // A missing folder: OpenEXR cannot open the temporary file.
    CHECK_THROWS_WITH_AS(vplkit::cli::write_exr(folder.path / "missing" / "x.exr", 2, 2, layers),
                         doctest::Contains("could not write"), vplkit::Error);
    CHECK(folder.names() == std::vector<std::string>{"taken.exr"});
}

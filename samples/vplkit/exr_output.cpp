#include "exr_output.hpp"

#include "vplkit/error.hpp"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>

#include <exception>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

namespace vplkit::cli {

namespace {

// Writes the layers to `file` (a new name: OpenEXR replaces what is there).
void write_layers(const std::string& file, uint32_t width, uint32_t height, std::span<const ExrLayer> layers,
                  const std::string& comment) {
    Imf::Header header(static_cast<int>(width), static_cast<int>(height));
    header.compression() = Imf::ZIP_COMPRESSION;  // lossless
    header.lineOrder() = Imf::INCREASING_Y;       // rows top to bottom, as the values are
    if (!comment.empty()) Imf::addComments(header, comment);
    Imf::FrameBuffer frame;
    // The half layers' values converted; kept until the pixels are written.
    std::vector<std::vector<Imath::half>> halves;
    halves.reserve(layers.size());
    for (const ExrLayer& layer : layers) {
        const size_t stride = layer.channels.size();
        const Imf::PixelType type = layer.half ? Imf::HALF : Imf::FLOAT;
        const char* base = reinterpret_cast<const char*>(layer.values.data());
        size_t bytes = sizeof(float);
        if (layer.half) {
            halves.emplace_back(layer.values.begin(), layer.values.end());
            base = reinterpret_cast<const char*>(halves.back().data());
            bytes = sizeof(Imath::half);
        }
        for (size_t c = 0; c < stride; ++c) {
            const std::string name = layer.name + "." + layer.channels[c];
            header.channels().insert(name, Imf::Channel(type));
            // OpenEXR's Slice takes a non-const pointer; writing only reads through it.
            frame.insert(name,
                         Imf::Slice(type, const_cast<char*>(base + c * bytes), stride * bytes, stride * bytes * width));
        }
    }
    Imf::OutputFile out(file.c_str(), header);
    out.setFrameBuffer(frame);
    out.writePixels(int(height));
}

}  // namespace

void write_exr(const std::filesystem::path& path, uint32_t width, uint32_t height, std::span<const ExrLayer> layers,
               const std::string& comment) {
    for (const ExrLayer& layer : layers) {
        const size_t expected = size_t(width) * height * layer.channels.size();
        if (width == 0 || height == 0 || layer.channels.empty() || layer.values.size() != expected) {
            throw Error("EXR " + path.string() + ": layer '" + layer.name + "' has " +
                        std::to_string(layer.values.size()) + " values, a " + std::to_string(width) + "x" +
                        std::to_string(height) + " image of " + std::to_string(layer.channels.size()) +
                        " channels needs " + std::to_string(expected));
        }
    }
    const std::filesystem::path temporary = path.string() + ".tmp" + std::to_string(::getpid());
    std::error_code ignored;
    try {
        // The file is finished when `out` closes; reading it back catches a short write there.
        write_layers(temporary.string(), width, height, layers, comment);
        if (!Imf::InputFile(temporary.c_str()).isComplete()) throw std::runtime_error("the file came out incomplete");
    } catch (const std::exception& e) {
        std::filesystem::remove(temporary, ignored);
        throw Error("could not write " + path.string() + ": " + e.what());
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::filesystem::remove(temporary, ignored);
        throw Error("could not write " + path.string() + ": " + error.message());
    }
}

}  // namespace vplkit::cli

#include "scene/gltf_images.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <climits>
#include <cstring>
#include <exception>
#include <span>
#include <system_error>
#include <thread>

namespace vplkit::scene::detail {
namespace {

bool is_data_uri(const std::string& uri) {
    return uri.rfind("data:", 0) == 0;
}

// URIs are percent-encoded (glTF 2.0 3.2.2); tinygltf decodes them the same way before opening.
std::string percent_decode(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit((unsigned char)uri[i + 1]) &&
            std::isxdigit((unsigned char)uri[i + 2])) {
            out.push_back(char(std::stoi(uri.substr(i + 1, 2), nullptr, 16)));
            i += 2;
        } else {
            out.push_back(uri[i]);
        }
    }
    return out;
}

std::string one_line(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

// Decodes one image with tinygltf's stb-based decoder (RGBA requested), reducing 16-bit
// channels to 8 bits. Returns an empty string or the problem.
std::string decode_one(int gltf_index, std::span<const uint8_t> encoded, Image& out) {
    try {
        if (encoded.size() > size_t(INT_MAX)) return "encoded image larger than 2 GiB";
        tinygltf::Image decoded;
        std::string err, warn;
        if (!tinygltf::LoadImageData(&decoded, gltf_index, &err, &warn, 0, 0, encoded.data(), int(encoded.size()),
                                     nullptr)) {
            return "cannot be decoded (" + one_line(err) + ")";
        }
        if (decoded.component != 4 || (decoded.bits != 8 && decoded.bits != 16) || decoded.width < 1 ||
            decoded.height < 1) {
            return "decoded to an unexpected format (" + std::to_string(decoded.component) + " channels of " +
                   std::to_string(decoded.bits) + " bits)";
        }
        out.width = uint32_t(decoded.width);
        out.height = uint32_t(decoded.height);
        const size_t values = size_t(out.width) * out.height * 4;
        if (decoded.bits == 8) {
            if (decoded.image.size() != values) return "decoded to the wrong number of bytes";
            out.rgba = std::move(decoded.image);
        } else {
            if (decoded.image.size() != values * 2) return "decoded to the wrong number of bytes";
            out.rgba.resize(values);
            for (size_t i = 0; i < values; ++i) {
                uint16_t v;
                std::memcpy(&v, decoded.image.data() + 2 * i, 2);
                out.rgba[i] = uint8_t((uint32_t(v) * 255u + 32767u) / 65535u);
            }
        }
        return {};
    } catch (const std::exception& e) {
        return std::string("cannot be decoded (") + e.what() + ")";
    }
}

}  // namespace

bool capture_image_bytes(tinygltf::Image* image, int image_index, std::string* /*err*/, std::string* /*warn*/,
                         int /*req_width*/, int /*req_height*/, const unsigned char* bytes, int size, void* user_data) {
    // An embedded image's pointer was computed from an unchecked bufferView: leave it alone.
    if (image->bufferView >= 0 || image_index < 0) return true;
    auto& captured = *static_cast<CapturedImages*>(user_data);
    const size_t index = size_t(image_index);
    if (captured.encoded.size() <= index) {
        captured.encoded.resize(index + 1);
        captured.captured.resize(index + 1, false);
    }
    captured.encoded[index].assign(bytes, bytes + std::max(size, 0));
    captured.captured[index] = true;
    return true;
}

std::vector<Image> decode_images(const GltfSource& source, const CapturedImages& captured,
                                 const std::vector<ImageUse>& uses, const std::filesystem::path& base_dir) {
    const auto& model = source.model;
    std::vector<Image> images(uses.size());
    std::vector<std::span<const uint8_t>> encoded(uses.size());
    std::vector<std::string> labels(uses.size());
    for (size_t k = 0; k < uses.size(); ++k) {
        const int index = uses[k].gltf_image;
        const tinygltf::Image& image = model.images[size_t(index)];
        Image& out = images[k];
        out.name = !image.uri.empty() && !is_data_uri(image.uri) ? image.uri
                   : !image.name.empty()                         ? image.name
                                                                 : "image " + std::to_string(index);
        out.srgb = uses[k].srgb;
        out.linear = uses[k].linear;
        labels[k] = "image " + std::to_string(index) + " ('" + out.name + "', " + uses[k].user + ")";
        if (image.bufferView >= 0) {
            encoded[k] = buffer_view_bytes(source, image.bufferView, labels[k]);
        } else if (size_t(index) < captured.captured.size() && captured.captured[size_t(index)]) {
            encoded[k] = captured.encoded[size_t(index)];
        } else if (!image.uri.empty() && !is_data_uri(image.uri)) {
            const std::filesystem::path file = base_dir / percent_decode(image.uri);
            std::error_code ec;
            source.fail("texture " + labels[k] + ": file " + file.string() +
                        (std::filesystem::exists(file, ec) ? " could not be read" : " not found"));
        } else {
            source.fail("texture " + labels[k] + " has no image data (neither a readable uri nor a bufferView)");
        }
    }

    std::vector<std::string> problems(uses.size());
    std::atomic<size_t> next{0};
    auto work = [&] {
        for (size_t k = next++; k < uses.size(); k = next++) {
            problems[k] = decode_one(uses[k].gltf_image, encoded[k], images[k]);
        }
    };
    const size_t thread_count = std::min<size_t>(std::max(1u, std::thread::hardware_concurrency()), uses.size());
    std::vector<std::thread> threads;
    for (size_t t = 1; t < thread_count; ++t) {
        try {
            threads.emplace_back(work);
        } catch (const std::system_error&) {
            break;  // no more threads to be had: the ones running (and this one) finish the work
        }
    }
    work();
    for (auto& thread : threads) thread.join();
    for (size_t k = 0; k < uses.size(); ++k) {
        if (!problems[k].empty()) source.fail("texture " + labels[k] + " " + problems[k]);
    }
    return images;
}

}  // namespace vplkit::scene::detail

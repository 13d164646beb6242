#pragma once
// Images: tinygltf's image callback only keeps the encoded bytes (see capture_image_bytes);
// decoding to RGBA8 happens afterwards, only for the images a material uses, on several threads,
// and only after an embedded image's bufferView has been bounds-checked (tinygltf hands the
// callback a pointer into the buffer without checking the bufferView fits).

#include "scene/gltf_accessors.hpp"
#include "vplkit/scene.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace vplkit::scene::detail {

struct CapturedImages {
    std::vector<std::vector<uint8_t>> encoded;  // by glTF image index
    std::vector<bool> captured;                 // the callback ran for this image with its file's bytes
};

// tinygltf::LoadImageDataFunction; user_data is a CapturedImages*.
bool capture_image_bytes(tinygltf::Image* image, int image_index, std::string* err, std::string* warn, int req_width,
                         int req_height, const unsigned char* bytes, int size, void* user_data);

struct ImageUse {
    int gltf_image = -1;
    std::string user;  // the first texture slot using it, for messages ("base colour of material 2 'floor'")
    bool srgb = false;
    bool linear = false;
};

// Decodes each used image to RGBA8 (16-bit images rounded to 8 bits), in the order of `uses`.
// Fails naming the image, its user and the problem (file missing, not decodable).
std::vector<Image> decode_images(const GltfSource& source, const CapturedImages& captured,
                                 const std::vector<ImageUse>& uses, const std::filesystem::path& base_dir);

}  // namespace vplkit::scene::detail

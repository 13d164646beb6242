#include "frame_exr.hpp"

#include "exr_output.hpp"

#include "vplkit/error.hpp"

#include <vector>

namespace vplkit::cli {

const char* const kFrameExrLayers =
    "beauty.RGB (linear radiance, direct + indirect), direct.RGB, indirect.RGB (with an indirect-light "
    "method), albedo.RGB (linear base colour), normal.XYZ (unit world-space shading normal), depth.Z "
    "(distance along the camera's forward axis in scene units, +inf where no surface was drawn), "
    "variance.Y (with a denoiser: its luminance variance of the demodulated indirect light); radiance, "
    "depth and variance as 32-bit floats, albedo and normal as 16-bit";

void write_frame_exr(const std::filesystem::path& path, const RenderedImage& image, const RenderSettings& settings) {
    if (image.depth.empty())
        throw Error("EXR " + path.string() + ": the frame was rendered without its G-buffer layers");
    // Radiance stays 32-bit: a sun-lit pixel can exceed 16-bit floats' 65504, and the float
    // file equals the PFM written from the same values.
    std::vector<ExrLayer> layers = {{"beauty", {"R", "G", "B"}, image.radiance, false},
                                    {"direct", {"R", "G", "B"}, image.direct, false}};
    if (settings.method != GiMethod::none) layers.push_back({"indirect", {"R", "G", "B"}, image.indirect, false});
    layers.push_back({"albedo", {"R", "G", "B"}, image.albedo, true});
    layers.push_back({"normal", {"X", "Y", "Z"}, image.normal, true});
    layers.push_back({"depth", {"Z"}, image.depth, false});
    if (!image.indirect_variance.empty()) layers.push_back({"variance", {"Y"}, image.indirect_variance, false});
    write_exr(path, image.width, image.height, layers, std::string("vplkit: ") + kFrameExrLayers);
}

}  // namespace vplkit::cli

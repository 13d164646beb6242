#pragma once
// A rendered frame as one layered EXR file (exr_output.hpp): beauty, direct, indirect (with an
// indirect-light method), albedo, normal, depth and, when the denoiser ran, its variance.

#include "vplkit/render_settings.hpp"
#include "vplkit/renderer.hpp"

#include <filesystem>

namespace vplkit::cli {

// The layers' names and channels, as the usage text and the file's comment list them.
extern const char* const kFrameExrLayers;

// `image` must have been rendered with settings.read_back_aovs. Throws vplkit::Error naming the
// file when it cannot be written (nothing is left there then).
void write_frame_exr(const std::filesystem::path& path, const RenderedImage& image, const RenderSettings& settings);

}  // namespace vplkit::cli

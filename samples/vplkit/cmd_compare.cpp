// `vplkit compare`: the error of a linear PFM image against a reference (ground truth) by the
// kit's metrics (image_metrics.hpp), and optionally a picture of where they differ.

#include "cli.hpp"
#include "commands.hpp"

#include "vplkit/error.hpp"
#include "vplkit/image_io.hpp"
#include "vplkit/image_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace vplkit::cli {

const char* const kCompareUsage =
    "usage: vplkit compare TEST.pfm REFERENCE.pfm [--diff OUT.png] [--scale S]\n"
    "\n"
    "Prints the error of TEST against REFERENCE, both linear RGB PFM files of one size, over all\n"
    "pixels and channels:\n"
    "  rmse           sqrt(mean (t - r)^2)\n"
    "  relative rmse  rmse / the reference's mean (as scripts/pfm_error.py)\n"
    "  relmse         mean (t - r)^2 / (r^2 + eps), eps = 0.01\n"
    "  ssim           SSIM (Wang et al. 2004: 11x11 Gaussian windows, sigma 1.5, K1 0.01, K2 0.03)\n"
    "                 on the linear values with L = the reference's largest value, per channel,\n"
    "                 averaged (not comparable with SSIM of tonemapped images)\n"
    "  --diff FILE    also write |t - r| x S per channel, clamped to 1, as an sRGB PNG\n"
    "  --scale S      the difference picture's gain (default 10)\n";

namespace {

float parse_scale(const std::string& text) {
    size_t used = 0;
    float value = NAN;
    try {
        value = std::stof(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (text.empty() || used != text.size() || !std::isfinite(value) || !(value > 0.0f)) {
        throw UsageError("--scale expects a positive number, got '" + text + "'");
    }
    return value;
}

std::string size_text(const PfmImage& image) { return std::to_string(image.width) + "x" + std::to_string(image.height); }

}  // namespace

int run_compare(Args& args) {
    std::optional<std::string> diff_path = args.value("--diff");
    float scale = 10.0f;
    if (auto text = args.value("--scale")) scale = parse_scale(*text);
    const std::optional<std::string> test_path = args.positional();
    const std::optional<std::string> reference_path = args.positional();
    args.finish();
    if (!test_path || !reference_path) throw UsageError("compare needs a test image and a reference image");
    if (diff_path && std::filesystem::path(*diff_path).extension() != ".png") {
        throw UsageError("--diff expects a .png file name, got '" + *diff_path + "'");
    }

    const PfmImage test = read_pfm(*test_path);
    const PfmImage reference = read_pfm(*reference_path);
    if (test.width != reference.width || test.height != reference.height) {
        throw Error("compare: " + *test_path + " is " + size_text(test) + ", the reference " + *reference_path + " is " +
                    size_text(reference) + "; the images must be the same size");
    }
    std::printf("test:          %s (%s)\n", test_path->c_str(), size_text(test).c_str());
    std::printf("reference:     %s (%s)\n", reference_path->c_str(), size_text(reference).c_str());

    std::printf("rmse:          %.6g\n", rmse(test.rgb, reference.rgb));
    double reference_sum = 0.0;
    for (float v : reference.rgb) reference_sum += v;
    const double reference_mean = reference_sum / double(reference.rgb.size());
    // A black (or negative) reference gives relative RMSE and SSIM's L nothing to scale by; the
    // absolute metrics still mean something, so print those and say why the others are missing.
    if (reference_mean > 0.0) {
        std::printf("relative rmse: %.6g (rmse / the reference's mean %.6g)\n", relative_rmse(test.rgb, reference.rgb),
                    reference_mean);
    } else {
        std::printf("relative rmse: n/a (the reference's mean is %.6g)\n", reference_mean);
    }
    std::printf("relmse:        %.6g (eps %g)\n", relative_mse(test.rgb, reference.rgb, kRelativeMseEpsilon),
                kRelativeMseEpsilon);
    const double reference_max = *std::max_element(reference.rgb.begin(), reference.rgb.end());
    if (reference_max > 0.0) {
        const SsimOptions options{.dynamic_range = reference_max};
        const double value = ssim(test.rgb, reference.rgb, test.width, test.height, options);
        const uint32_t window = ssim_window_size(test.width, test.height);
        std::printf("ssim:          %.6f (linear values, L = %.6g = the reference's max, %ux%u windows)\n", value,
                    reference_max, window, window);
    } else {
        std::printf("ssim:          n/a (the reference's largest value is %.6g)\n", reference_max);
    }

    if (diff_path) {
        const std::vector<uint8_t> rgba = difference_image_rgba8(test.rgb, reference.rgb, test.width, test.height, scale);
        write_png(*diff_path, test.width, test.height, rgba);
        std::printf("wrote %s (|test - reference| x %g, sRGB)\n", diff_path->c_str(), scale);
    }
    return 0;
}

}  // namespace vplkit::cli

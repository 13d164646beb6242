// `vplkit compare`: the error of an image against a reference (ground truth) by the kit's metrics
// (image_metrics.hpp), and optionally a picture of where they differ. Two kinds of input, never
// mixed: linear PFM (the renderer's radiance) or PNG (the tonemapped sRGB frame a viewer sees,
// which is what the GI sampling papers score with RMSE and SSIM).

#include "cli.hpp"
#include "cli_checks.hpp"
#include "commands.hpp"

#include "vplkit/error.hpp"
#include "vplkit/image_io.hpp"
#include "vplkit/image_metrics.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace vplkit::cli {

namespace {

struct CompareOptions {
    std::string test_path, reference_path;
    std::string diff_path;  // "" = none
    float scale = 10.0f;
};

// An image as the metrics take it: 3 floats per pixel, rows top to bottom.
struct Values {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<float> rgb;
};

std::string size_text(const Values& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
}

bool is_png_name(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension == ".png";
}

Values read_values(const std::string& path, bool png) {
    if (!png) {
        PfmImage pfm = read_pfm(path);
        return Values{pfm.width, pfm.height, std::move(pfm.rgb)};
    }
    // The codes as stored, / 255: the display-referred values the papers score, so no sRGB
    // decode; alpha dropped (vplkit writes 255, and a viewer's backdrop is not the image's).
    const PngImage png_image = read_png(path);
    Values values{png_image.width, png_image.height, {}};
    const size_t pixels = size_t(values.width) * values.height;
    values.rgb.resize(pixels * 3);
    for (size_t p = 0; p < pixels; ++p) {
        for (size_t c = 0; c < 3; ++c) values.rgb[p * 3 + c] = float(png_image.rgba[p * 4 + c]) / 255.0f;
    }
    return values;
}

int run_compare(const CompareOptions& options) {
    const std::optional<std::string> diff_path =
        options.diff_path.empty() ? std::nullopt : std::optional<std::string>(options.diff_path);
    const float scale = options.scale;
    if (options.reference_path.empty()) throw UsageError("compare needs a test image and a reference image");
    const std::string* test_path = &options.test_path;
    const std::string* reference_path = &options.reference_path;
    if (diff_path && std::filesystem::path(*diff_path).extension() != ".png") {
        throw UsageError("--diff expects a .png file name, got '" + *diff_path + "'");
    }

    const bool png = is_png_name(*test_path);
    if (png != is_png_name(*reference_path)) {
        const std::string& png_path = png ? *test_path : *reference_path;
        const std::string& other_path = png ? *reference_path : *test_path;
        throw UsageError("compare: " + png_path + " is a PNG and " + other_path +
                         " is not; compare two PNG files (tonemapped) or two PFM files (linear)");
    }

    const Values test = read_values(*test_path, png);
    const Values reference = read_values(*reference_path, png);
    if (test.width != reference.width || test.height != reference.height) {
        throw Error("compare: " + *test_path + " is " + size_text(test) + ", the reference " + *reference_path +
                    " is " + size_text(reference) + "; the images must be the same size");
    }
    std::printf("test:          %s (%s)\n", test_path->c_str(), size_text(test).c_str());
    std::printf("reference:     %s (%s)\n", reference_path->c_str(), size_text(reference).c_str());
    if (png) {
        std::printf("values:        tonemapped sRGB codes / 255 (PNG, alpha ignored), SSIM with L = 1\n");
    } else {
        std::printf("values:        linear RGB (PFM), SSIM with L = the reference's max\n");
    }

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
    const uint32_t window = ssim_window_size(test.width, test.height);
    if (png) {
        // [0, 1] values have a fixed range, so L = 1 needs nothing from the reference (a black
        // frame is scored too) and the number compares with other tools' SSIM of 8-bit images.
        const double value = ssim(test.rgb, reference.rgb, test.width, test.height, SsimOptions{.dynamic_range = 1.0});
        std::printf("ssim:          %.6f (sRGB / 255, L = 1, %ux%u windows)\n", value, window, window);
    } else {
        const double reference_max = *std::max_element(reference.rgb.begin(), reference.rgb.end());
        if (reference_max > 0.0) {
            const SsimOptions options{.dynamic_range = reference_max};
            const double value = ssim(test.rgb, reference.rgb, test.width, test.height, options);
            std::printf("ssim:          %.6f (linear values, L = %.6g = the reference's max, %ux%u windows)\n", value,
                        reference_max, window, window);
        } else {
            std::printf("ssim:          n/a (the reference's largest value is %.6g)\n", reference_max);
        }
    }

    if (diff_path) {
        const std::vector<uint8_t> rgba =
            difference_image_rgba8(test.rgb, reference.rgb, test.width, test.height, scale);
        write_png(*diff_path, test.width, test.height, rgba);
        // The same picture for both inputs: the difference of the values the metrics saw, sRGB-encoded
        // for display. For PNG input those values are already sRGB, so this encodes them a second
        // time; kept so one brightness means one difference whatever the input (see the usage).
        std::printf("wrote %s (|test - reference| x %g of the %s values, sRGB-encoded)\n", diff_path->c_str(), scale,
                    png ? "sRGB / 255" : "linear");
    }
    return 0;
}

}  // namespace

void add_compare(CLI::App& vplkit, Runners& runners) {
    CLI::App* compare = add_command(
        vplkit, "compare",
        "error of a PFM or PNG image against a reference: RMSE, relative RMSE, relMSE, SSIM; difference PNG",
        "Prints the error of TEST against REFERENCE, two images of one size, over all pixels and channels. Both are "
        "PFM or both are PNG (by the .png extension; a mix is refused).\n"
        "  PFM: linear RGB values as stored (HDR radiance).\n"
        "  PNG: the 8-bit sRGB codes / 255, in [0, 1]: the tonemapped frame as a viewer sees it, not linearized; "
        "alpha is ignored (what the GI papers' RMSE and SSIM use).\n"
        "  rmse: sqrt(mean (t - r)^2); relative rmse: rmse / the reference's mean (as scripts/pfm_error.py); "
        "relmse: mean (t - r)^2 / (r^2 + eps), eps = 0.01.\n"
        "  ssim: SSIM (Wang et al. 2004: 11x11 Gaussian windows, sigma 1.5, K1 0.01, K2 0.03) per channel, "
        "averaged; dynamic range L = 1 for PNG (the standard setting for [0, 1] images), L = the reference's "
        "largest value for PFM (not comparable with SSIM of tonemapped images).");
    auto options = std::make_shared<CompareOptions>();
    compare->add_option("TEST", options->test_path, "the image to score (.pfm or .png)");
    compare->add_option("REFERENCE", options->reference_path, "the reference, of the same kind and size");
    compare
        ->add_option("--diff", options->diff_path,
                     "also write |t - r| x S per channel of the values above, clamped to 1 and sRGB-encoded for "
                     "display, as a PNG (for PNG input: the difference of the sRGB values, encoded once more, so "
                     "small differences show brighter)")
        ->option_text("FILE.png");
    number(compare->add_option("--scale", options->scale, "the difference picture's gain")->capture_default_str(), "S",
           NumberRange::above(0.0));
    runners.push_back({compare, [options] { return run_compare(*options); }});
}

}  // namespace vplkit::cli

// bench gi's ground truth (bench_gi_truth.hpp).

#include "bench_gi_truth.hpp"

#include "bench_gi.hpp"

#include "vplkit/cache_key.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image_io.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_setups.hpp"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

namespace vplkit::cli {

namespace {

std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Everything the exact frame depends on.
std::string ground_truth_key(const scene::Setup& setup, const scene::Scene& scene, const RenderSettings& s) {
    std::ostringstream key;
    key.precision(9);
    const scene::Camera& c = scene.camera();
    key << "vplkit exact ground truth v1\nsetup " << setup.name << "\nscene " << setup.scene.string() << "\ncamera "
        << c.position.x << ' ' << c.position.y << ' ' << c.position.z << ' ' << c.forward.x << ' ' << c.forward.y << ' '
        << c.forward.z << ' ' << c.up.x << ' ' << c.up.y << ' ' << c.up.z << ' ' << c.yfov << "\n";
    if (c.projection == scene::Projection::orthographic) {
        key << "orthographic " << c.ymag << ' ' << c.znear << ' ' << c.zfar << "\n";
    }
    for (const scene::Light& l : scene.lights) {
        key << "light " << int(l.type) << ' ' << l.color.x << ' ' << l.color.y << ' ' << l.color.z << ' ' << l.intensity
            << ' ' << l.position.x << ' ' << l.position.y << ' ' << l.position.z << ' ' << l.direction.x << ' '
            << l.direction.y << ' ' << l.direction.z << ' ' << l.range << ' ' << l.inner_cone_angle << ' '
            << l.outer_cone_angle << "\n";
    }
    key << "emissive triangles " << scene.emissive_triangles.size() << "\nsize " << s.width << 'x' << s.height
        << "\nvpls " << (s.vpl_source == VplSource::brsm ? "brsm" : "ir") << ' ' << s.vpl_paths << ' ' << s.vpl_bounces
        << ' ' << s.brsm.vpl_count << ' ' << s.brsm.samples_per_texel << ' ' << s.brsm.defensive_fraction << ' '
        << s.rsm_resolution << "\nseed " << s.seed << "\nexposure " << s.exposure << "\n";
    return key.str();
}

}  // namespace

GroundTruth bench_ground_truth(Renderer& renderer, const scene::Setup& setup, const scene::Scene& scene,
                               const RenderSettings& base, const std::filesystem::path& cache) {
    GroundTruth truth;
    RenderSettings s = base;
    s.method = GiMethod::exact;
    const std::string key = ground_truth_key(setup, scene, s);
    const std::filesystem::path stem = cache / ("exact-" + fnv1a_hex(key));
    truth.png = stem.string() + ".png";
    const std::filesystem::path pfm = stem.string() + ".pfm", key_file = stem.string() + ".key";
    if (std::filesystem::exists(key_file) && read_text(key_file) == key && std::filesystem::exists(pfm) &&
        std::filesystem::exists(truth.png)) {
        const PngImage png = read_png(truth.png);
        truth.rgb = unit_rgb(png.rgba);
        truth.radiance = read_pfm(pfm).rgb;
        truth.cached = true;
        std::printf("ground truth: cached %s\n", pfm.string().c_str());
    } else {
        s.progress = [](uint32_t done, uint32_t total) {
            if (isatty(fileno(stderr))) {
                std::fprintf(stderr, "\r[bench] ground truth: %u/%u VPLs", done, total);
                if (done == total) std::fprintf(stderr, "\n");
            } else if (done == total || done % 1024 < 32) {
                std::fprintf(stderr, "[bench] ground truth: %u/%u VPLs\n", done, total);
            }
        };
        const auto start = std::chrono::steady_clock::now();
        const RenderedImage image = renderer.render(scene.camera(), s);
        truth.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (image.non_finite_pixels > 0) throw Error("bench: the ground truth has non-finite pixels");
        write_png(truth.png, image.width, image.height, image.rgba8);
        write_pfm(pfm, image.width, image.height, image.radiance);
        std::ofstream(key_file, std::ios::binary) << key;
        truth.rgb = unit_rgb(image.rgba8);
        truth.radiance = image.radiance;
        std::printf("ground truth: %u VPLs, %.1f s (host wall clock), cached as %s\n", image.vpl_count,
                    truth.wall_ms / 1000.0, pfm.string().c_str());
    }
    return truth;
}

}  // namespace vplkit::cli

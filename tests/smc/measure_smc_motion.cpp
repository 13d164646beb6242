// measure_smc_motion: where SMC's indirect light departs from the reference in a moving scene (not
// a test; its figures are in docs/smc.md). The animated box (scenes/animated_box: the tall block
// turns, the spot swings) from the set-up's camera, F frames at 6 per second: each frame's SMC
// indirect light (exact gather) against an exact gather over many IR paths, as the mean over the
// image and over the pixels that moved (the block) and the rest, and the VPL set itself (a twin
// renderer with the same seed keeps the same set): VPLs and flux on the tall block against the
// reference's IR VPLs there. Writes DIR/smc_NNNN.pfm and DIR/reference_NNNN.pfm (indirect).
//   measure_smc_motion [frames=6] [size=48] [budget=512] [dir=/tmp/measure_smc_motion] [animation|all]

#include "vplkit/context.hpp"
#include "vplkit/image_io.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_pose.hpp"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace {

const std::string kScene = std::string(VPLKIT_SOURCE_DIR) + "/scenes/animated_box/animated_box.gltf";

double luminance(const std::vector<float>& rgb, size_t pixel) {
    return 0.2126 * rgb[3 * pixel] + 0.7152 * rgb[3 * pixel + 1] + 0.0722 * rgb[3 * pixel + 2];
}

// On the tall block (0.6 x 1.2 x 0.6 about (-0.35, 0.6, -0.3), turning about Y): within its
// circumscribed cylinder and below its top, off the box's walls and floor.
bool on_tall_block(const glm::vec3& p) {
    const float dx = p.x + 0.35f, dz = p.z + 0.3f;
    return dx * dx + dz * dz < 0.43f * 0.43f && p.y > 0.01f && p.y < 1.21f && p.z > -0.99f && p.x > -0.99f;
}

struct SetFlux {
    size_t count = 0, block_count = 0;
    double flux = 0.0, block_flux = 0.0;
    size_t face_count[5] = {0, 0, 0, 0, 0};
    double face_flux[5] = {0, 0, 0, 0, 0};  // the block's top, then its sides by the normal's azimuth
};

int block_face(const glm::vec3& n) {
    if (n.y > 0.9f) return 0;
    const float a = std::atan2(n.z, n.x) + 3.14159265f;  // 0 .. 2 pi
    return 1 + std::min(3, int(a / (0.5f * 3.14159265f)));
}

SetFlux set_flux(const std::vector<vplkit::VplPoint>& vpls) {
    SetFlux s;
    for (const auto& v : vpls) {
        const double f = 0.2126 * v.flux.x + 0.7152 * v.flux.y + 0.0722 * v.flux.z;
        ++s.count;
        s.flux += f;
        if (on_tall_block(v.position)) {
            ++s.block_count;
            s.block_flux += f;
            const int face = block_face(v.normal);
            ++s.face_count[face];
            s.face_flux[face] += f;
        }
    }
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    const uint32_t frames = argc > 1 ? uint32_t(std::atoi(argv[1])) : 6;
    const uint32_t size = argc > 2 ? uint32_t(std::atoi(argv[2])) : 48;
    const uint32_t budget = argc > 3 ? uint32_t(std::atoi(argv[3])) : 512;
    const std::filesystem::path dir = argc > 4 ? argv[4] : "/tmp/measure_smc_motion";
    const std::string animation = argc > 5 ? argv[5] : "all";
    if (frames < 1 || size < 8 || budget < 1) {
        std::fprintf(stderr, "usage: measure_smc_motion [frames] [size] [budget] [dir] [animation|all]\n");
        return 2;
    }
    std::filesystem::create_directories(dir);
    auto context = vplkit::Context::create({});
    vplkit::scene::LoadOptions load;
    if (animation != "all") load.animation = animation;
    vplkit::scene::PosableScene posable(kScene, load);
    vplkit::scene::Camera camera =
        vplkit::scene::look_at({0.0f, 1.0f, 3.4f}, {0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, glm::radians(45.0f));
    camera.aspect = 1.0f;
    camera.znear = 0.01f;
    camera.zfar = 100.0f;

    vplkit::RenderSettings smc;
    smc.width = smc.height = size;
    smc.method = vplkit::GiMethod::exact;
    smc.vpl_source = vplkit::VplSource::smc;
    smc.smc.budget = budget;
    smc.read_back_aovs = true;
    smc.half_resolution_gi = false;
    smc.denoise = vplkit::DenoiseMode::off;
    smc.antialias = false;
    vplkit::RenderSettings smc_vpls = smc;
    smc_vpls.vpls_only = true;
    vplkit::RenderSettings reference = smc;
    reference.vpl_source = vplkit::VplSource::ir;
    reference.vpl_paths = 16384;
    reference.seed = 1000003;
    vplkit::RenderSettings reference_vpls = reference;
    reference_vpls.vpls_only = true;

    vplkit::Renderer smc_renderer(*context, posable.scene()), twin(*context, posable.scene()),
        reference_renderer(*context, posable.scene());
    std::printf("%5s %8s %8s %8s %8s | %6s %6s %9s %9s | %9s %9s | %s\n", "frame", "all", "block", "rest", "|E|",
                "vpls", "block", "flux", "blockflux", "ref flux", "ref block", "smc counts");
    for (uint32_t f = 0; f < frames; ++f) {
        if (f > 0) {
            const vplkit::scene::PoseChange change = posable.pose(double(f) / 6.0);
            smc_renderer.update_pose(change);
            twin.update_pose(change);
            reference_renderer.update_pose(change);
        }
        smc.frame = smc_vpls.frame = reference.frame = reference_vpls.frame = f;
        const vplkit::RenderedImage image = smc_renderer.render(camera, smc);
        const vplkit::RenderedImage set = twin.render(camera, smc_vpls);
        char name[64];
        std::snprintf(name, sizeof name, "smc_%04u.pfm", f);
        vplkit::write_pfm(dir / name, size, size, image.indirect);
        // The reference's image and flux, kept in DIR for the next run of the same frames.
        std::snprintf(name, sizeof name, "reference_%04u.pfm", f);
        const std::filesystem::path truth_file = dir / name;
        const std::filesystem::path flux_file = truth_file.string() + ".flux";
        vplkit::RenderedImage truth;
        SetFlux r;
        if (std::filesystem::exists(flux_file)) {
            truth.indirect = vplkit::read_pfm(truth_file).rgb;
            std::FILE* in = std::fopen(flux_file.c_str(), "r");
            if (!in || std::fscanf(in, "%zu %zu %lf %lf", &r.count, &r.block_count, &r.flux, &r.block_flux) != 4) {
                std::fprintf(stderr, "%s: unreadable\n", flux_file.c_str());
                return 1;
            }
            std::fclose(in);
        } else {
            truth = reference_renderer.render(camera, reference);
            r = set_flux(reference_renderer.render(camera, reference_vpls).vpls);
            vplkit::write_pfm(truth_file, size, size, truth.indirect);
            std::FILE* out = std::fopen(flux_file.c_str(), "w");
            std::fprintf(out, "%zu %zu %.9g %.9g\n", r.count, r.block_count, r.flux, r.block_flux);
            std::fclose(out);
        }
        double sum[2] = {0, 0}, ref[2] = {0, 0}, error = 0.0;
        for (size_t p = 0; p < size_t(size) * size; ++p) {
            const bool moved =
                image.motion[3 * p] != 0.0f || image.motion[3 * p + 1] != 0.0f || image.motion[3 * p + 2] != 0.0f;
            const double a = luminance(image.indirect, p), b = luminance(truth.indirect, p);
            sum[moved] += a;
            ref[moved] += b;
            error += std::abs(a / (1.0 + a) - b / (1.0 + b));
        }
        const SetFlux s = set_flux(set.vpls);
        std::printf("%5u %8.4f %8.4f %8.4f %8.5f | %6zu %6zu %9.4f %9.4f | %9.4f %9.4f | invalid %u moved %u\n", f,
                    (sum[0] + sum[1]) / (ref[0] + ref[1]), ref[1] > 0 ? sum[1] / ref[1] : 0.0, sum[0] / ref[0],
                    error / (double(size) * size), s.count, s.block_count, s.flux, s.block_flux, r.flux, r.block_flux,
                    set.smc ? set.smc->invalid : 0u, set.smc ? set.smc->moved : 0u);
        if (!std::filesystem::exists(flux_file.string() + ".faces")) {
            const SetFlux faces = set_flux(reference_renderer.render(camera, reference_vpls).vpls);
            std::FILE* out = std::fopen((flux_file.string() + ".faces").c_str(), "w");
            for (int face = 0; face < 5; ++face) std::fprintf(out, "%.9g ", faces.face_flux[face]);
            std::fclose(out);
        }
        std::FILE* in = std::fopen((flux_file.string() + ".faces").c_str(), "r");
        std::printf("      faces (top, sides by azimuth): smc count/flux, reference flux:");
        for (int face = 0; face < 5; ++face) {
            double reference_flux = 0.0;
            if (std::fscanf(in, "%lf", &reference_flux) != 1) reference_flux = 0.0;
            std::printf("  %zu/%.3f %.3f", s.face_count[face], s.face_flux[face], reference_flux);
        }
        std::fclose(in);
        std::printf("\n");
        std::fflush(stdout);
    }
    return 0;
}

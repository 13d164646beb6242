// The G-buffer convention check (stages/gbuffer_check.hpp) on lavapipe: the in-repo Cornell box's
// own G-buffer, from a camera moved aside and rolled (view space is not world space), gives the
// depth and normals a renderer would have; the adapter runs on them with correct options and
// with one option wrong at a time, and the check must name that option (and nothing on correct
// ones). The shares are printed: they set the thresholds of gbuffer_check.hpp.

#include "raster_test_scenes.hpp"
#include "vplkit/camera_view.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/gpu_scene.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/stages/gbuffer.hpp"
#include "vplkit/stages/gbuffer_adapter.hpp"
#include "vplkit/stages/gbuffer_check.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace {

using vplkit::stages::DepthConvention;
using vplkit::stages::GbufferNormalEncoding;
using vplkit::stages::GbufferNormalSpace;

constexpr uint32_t kWidth = 64, kHeight = 48;

struct Renderer {
    std::vector<glm::vec4> world_normal, albedo;
    std::vector<float> depth;  // standard Z
    glm::mat4 view_projection{1.0f};
    glm::mat3 view_to_world{1.0f};
    glm::vec3 eye{0.0f};
};

// What a renderer would hand the adapter: the kit's own G-buffer of the Cornell box.
const Renderer& renderer(vplkit::Context& ctx) {
    static const Renderer r = [&ctx] {
        raster_test::RolledCornellGbuffer kit = raster_test::rolled_cornell_gbuffer(ctx, kWidth, kHeight);
        Renderer out;
        out.view_projection = kit.view.view_projection;
        out.view_to_world = kit.view_to_world;
        out.eye = kit.view.position;
        out.world_normal = std::move(kit.normal);
        out.albedo = std::move(kit.albedo);
        out.depth = std::move(kit.depth);
        return out;
    }();
    return r;
}

// How the renderer stored its images (the truth) and what it told the adapter.
struct Stored {
    DepthConvention depth = DepthConvention::standard;
    GbufferNormalSpace space = GbufferNormalSpace::world;
    GbufferNormalEncoding encoding = GbufferNormalEncoding::xyz;  // xyz or xyz_unorm, in RGBA32F
};

vplkit::stages::GbufferCheck run_check(vplkit::Context& ctx, const Stored& stored,
                                       const vplkit::stages::GbufferAdapterOptions& options) {
    const Renderer& r = renderer(ctx);
    std::vector<float> depth = r.depth;
    if (stored.depth == DepthConvention::reversed) {
        for (float& d : depth) d = 1.0f - d;
    }
    std::vector<glm::vec4> normal = r.world_normal;
    for (glm::vec4& n : normal) {
        glm::vec3 v(n);
        if (stored.space == GbufferNormalSpace::view) v = glm::transpose(r.view_to_world) * v;
        if (stored.encoding == GbufferNormalEncoding::xyz_unorm) v = v * 0.5f + 0.5f;
        n = glm::vec4(v, 0.0f);
    }
    auto sampled = [&ctx](VkFormat format, const char* name) {
        return vplkit::Image::create(ctx, kWidth, kHeight, format, VK_IMAGE_USAGE_SAMPLED_BIT, name);
    };
    auto depth_image = sampled(VK_FORMAT_D32_SFLOAT, "renderer depth");
    depth_image.upload(depth);
    auto normal_image = sampled(VK_FORMAT_R32G32B32A32_SFLOAT, "renderer normal");
    normal_image.upload(normal);
    auto albedo_image = sampled(VK_FORMAT_R32G32B32A32_SFLOAT, "renderer albedo");
    albedo_image.upload(r.albedo);

    auto out = vplkit::GbufferImages::create(ctx, kWidth, kHeight);
    vplkit::PassList passes("gbuffer check: adapter");
    vplkit::stages::add_gbuffer_adapter_pass(ctx, passes, {depth_image, normal_image, albedo_image, {}}, options, out);
    passes.run(ctx);
    const std::vector<glm::vec4> position = raster_test::download_rgba(out.position);
    const std::vector<glm::vec4> shading = raster_test::download_rgba(out.normal);
    const std::vector<glm::vec4> geometric = raster_test::download_rgba(out.geometric_normal);
    const vplkit::stages::GbufferCheck check =
        vplkit::stages::check_gbuffer_conventions({position, shading, geometric}, options, r.eye);
    MESSAGE("covered " << check.covered_share << ", outside " << check.outside_share << ", facing away "
                       << check.facing_away_share << ", disagreeing " << check.disagreeing_share << ", median angle "
                       << check.median_angle_degrees << ", other space " << check.other_space_median_angle_degrees
                       << ", eye offset " << check.eye_offset);
    for (const std::string& p : check.problems()) MESSAGE(p);
    return check;
}

// The options that match `stored`.
vplkit::stages::GbufferAdapterOptions correct_options(vplkit::Context& ctx, const Stored& stored) {
    const Renderer& r = renderer(ctx);
    glm::mat4 reverse(1.0f);  // clip z -> w - z: a reversed-Z projection is reverse x the standard one
    reverse[2][2] = -1.0f;
    reverse[3][2] = 1.0f;
    vplkit::stages::GbufferAdapterOptions o;
    o.inverse_view_projection =
        glm::inverse(stored.depth == DepthConvention::reversed ? reverse * r.view_projection : r.view_projection);
    o.depth = stored.depth;
    o.normal_space = stored.space;
    o.normal_encoding = stored.encoding;
    o.view_to_world = r.view_to_world;
    return o;
}

bool mentions(const std::vector<std::string>& problems, const std::string& option) {
    for (const std::string& p : problems) {
        if (p.find(option) != std::string::npos) return true;
    }
    return false;
}

}  // namespace

TEST_CASE("gbuffer check: correct conventions give no problem") {
    vplkit::Context& ctx = vplkit::test::context();
    const Stored cases[] = {
        {DepthConvention::standard, GbufferNormalSpace::world, GbufferNormalEncoding::xyz},
        {DepthConvention::reversed, GbufferNormalSpace::view, GbufferNormalEncoding::xyz_unorm},
    };
    for (const Stored& stored : cases) {
        const auto check = run_check(ctx, stored, correct_options(ctx, stored));
        CHECK(check.covered_share > 0.5);
        CHECK(check.problems().empty());
    }
}

TEST_CASE("gbuffer check: GiChain's options and frame are those the adapter ran with") {
    vplkit::Context& ctx = vplkit::test::context();
    const Renderer& r = renderer(ctx);
    const Stored stored{DepthConvention::standard, GbufferNormalSpace::view, GbufferNormalEncoding::xyz};
    const auto direct = run_check(ctx, stored, correct_options(ctx, stored));
    vplkit::stages::GbufferAdapterOptions adapter;  // the matrices come from the frame
    adapter.normal_space = GbufferNormalSpace::view;
    const std::vector<glm::vec4> none(1);
    const vplkit::stages::GiChainFrame frame{0, r.eye, r.view_projection, r.view_to_world};
    const auto via_chain = vplkit::stages::check_gbuffer_conventions({none, none, none}, adapter, frame);
    CHECK(via_chain.options.inverse_view_projection == direct.options.inverse_view_projection);
    CHECK(via_chain.options.view_to_world == direct.options.view_to_world);
    CHECK(via_chain.options.normal_space == GbufferNormalSpace::view);
}

TEST_CASE("gbuffer check: reversed Z declared standard is named") {
    vplkit::Context& ctx = vplkit::test::context();
    const Stored stored{DepthConvention::reversed, GbufferNormalSpace::world, GbufferNormalEncoding::xyz};
    vplkit::stages::GbufferAdapterOptions options = correct_options(ctx, stored);
    options.depth = DepthConvention::standard;
    const auto problems = run_check(ctx, stored, options).problems();
    CHECK(mentions(problems, "set depth = DepthConvention::reversed"));
    CHECK_FALSE(mentions(problems, "normal_space"));
    CHECK_FALSE(mentions(problems, "normal_encoding"));
}

TEST_CASE("gbuffer check: an inverse view-projection other than the depth's is named") {
    vplkit::Context& ctx = vplkit::test::context();
    const Stored stored{DepthConvention::reversed, GbufferNormalSpace::world, GbufferNormalEncoding::xyz};
    vplkit::stages::GbufferAdapterOptions options = correct_options(ctx, stored);
    // The standard projection's inverse for a reversed-Z depth (depth declared right).
    options.inverse_view_projection = glm::inverse(renderer(ctx).view_projection);
    auto problems = run_check(ctx, stored, options).problems();
    CHECK(mentions(problems, "inverse_view_projection"));
    CHECK_FALSE(mentions(problems, "normal_space"));
    // Last frame's: the camera a little to the left.
    const Stored standard{};
    options = correct_options(ctx, standard);
    const glm::mat4 moved = glm::translate(glm::mat4(1.0f), glm::vec3(0.05f, 0.0f, 0.0f));
    options.inverse_view_projection = glm::inverse(renderer(ctx).view_projection * moved);
    problems = run_check(ctx, standard, options).problems();
    CHECK(mentions(problems, "the camera that inverse_view_projection describes"));
}

TEST_CASE("gbuffer check: view-space normals declared world are named") {
    vplkit::Context& ctx = vplkit::test::context();
    const Stored stored{DepthConvention::standard, GbufferNormalSpace::view, GbufferNormalEncoding::xyz};
    vplkit::stages::GbufferAdapterOptions options = correct_options(ctx, stored);
    options.normal_space = GbufferNormalSpace::world;
    const auto problems = run_check(ctx, stored, options).problems();
    CHECK(mentions(problems, "set normal_space = GbufferNormalSpace::view"));
    CHECK_FALSE(mentions(problems, "DepthConvention"));
}

TEST_CASE("gbuffer check: a normal encoding other than the image's is named") {
    vplkit::Context& ctx = vplkit::test::context();
    // n * 0.5 + 0.5 read as n, and n read as n * 0.5 + 0.5.
    const Stored cases[] = {
        {DepthConvention::standard, GbufferNormalSpace::world, GbufferNormalEncoding::xyz_unorm},
        {DepthConvention::standard, GbufferNormalSpace::world, GbufferNormalEncoding::xyz},
    };
    for (const Stored& stored : cases) {
        vplkit::stages::GbufferAdapterOptions options = correct_options(ctx, stored);
        options.normal_encoding = stored.encoding == GbufferNormalEncoding::xyz ? GbufferNormalEncoding::xyz_unorm
                                                                                : GbufferNormalEncoding::xyz;
        const auto problems = run_check(ctx, stored, options).problems();
        CHECK(mentions(problems, "normal_encoding"));
        CHECK_FALSE(mentions(problems, "DepthConvention"));
    }
}

TEST_CASE("gbuffer check: no surface at all names the depth convention") {
    const std::vector<glm::vec4> background(16, glm::vec4(0.0f));
    const auto check =
        vplkit::stages::check_gbuffer_conventions({background, background, background}, {}, glm::vec3(0.0f));
    CHECK(check.covered_share == 0.0);
    CHECK(mentions(check.problems(), "no pixel has a surface"));
    CHECK(mentions(check.problems(), "set depth = DepthConvention::reversed"));
}

TEST_CASE("gbuffer check: images of different sizes are refused") {
    const std::vector<glm::vec4> four(4), three(3);
    CHECK_THROWS_WITH_AS(vplkit::stages::check_gbuffer_conventions({four, four, three}, {}, glm::vec3(0.0f)),
                         doctest::Contains("one size"), vplkit::Error);
}

// `vplkit render` and `vplkit sequence` run as programs (lavapipe, validation on) and their files
// read back: the layered EXR through the OpenEXR library against the PFM of the same run and the
// frame's own invariants, and the --stats JSON through nlohmann-json.

#include "test_files.hpp"

#include "vplkit/image_io.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <nlohmann/json.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// Runs vplkit with `arguments` on the CPU device with validation on; its output in `log`. Fails
// the test on a non-zero exit or a validation message.
void run_vplkit(const std::string& arguments, const std::filesystem::path& log) {
    const std::string command = std::string("\"") + VPLKIT_EXE + "\" " + arguments + " --device cpu --validation > \"" +
                                log.string() + "\" 2>&1";
    const int status = std::system(command.c_str());
    const std::string output = read_text(log);
    CAPTURE(command);
    CAPTURE(output);
    REQUIRE(status == 0);
    CHECK(output.find("[validation") == std::string::npos);
}

std::set<std::string> channel_names(const Imf::InputFile& file) {
    std::set<std::string> names;
    const Imf::ChannelList& channels = file.header().channels();
    for (auto it = channels.begin(); it != channels.end(); ++it) names.insert(it.name());
    return names;
}

// The named channels of `file` as floats, a pixel's channels together, rows top to bottom.
std::vector<float> read_channels(Imf::InputFile& file, const std::vector<std::string>& names) {
    const Imath::Box2i window = file.header().dataWindow();
    const size_t width = size_t(window.max.x - window.min.x + 1), height = size_t(window.max.y - window.min.y + 1);
    const size_t n = names.size();
    std::vector<float> values(width * height * n);
    Imf::FrameBuffer frame;
    for (size_t c = 0; c < n; ++c) {
        frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data() + c), sizeof(float) * n,
                                          sizeof(float) * n * width));
    }
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return values;
}

}  // namespace

TEST_CASE("render writes a layered EXR whose beauty is its PFM and whose stats parse back") {
    vplkit::test::ScratchFolder folder("render-exr");
    const auto exr = folder.path / "frame.exr", pfm = folder.path / "frame.pfm", stats = folder.path / "stats.json";
    run_vplkit("render --scene cornell --width 32 --height 32 --method hybrid --denoise svgf --frames 2 --out \"" +
                   exr.string() + "\" --out-hdr \"" + pfm.string() + "\" --stats \"" + stats.string() + "\"",
               folder.path / "log.txt");
    CHECK(folder.names() == std::vector<std::string>{"frame.exr", "frame.pfm", "log.txt", "stats.json"});

    Imf::InputFile file(exr.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    REQUIRE(window.max.x - window.min.x + 1 == 32);
    REQUIRE(window.max.y - window.min.y + 1 == 32);
    const std::set<std::string> expected = {"beauty.R", "beauty.G",   "beauty.B",   "direct.R",   "direct.G",
                                            "direct.B", "indirect.R", "indirect.G", "indirect.B", "albedo.R",
                                            "albedo.G", "albedo.B",   "normal.X",   "normal.Y",   "normal.Z",
                                            "depth.Z",  "variance.Y"};
    CHECK(channel_names(file) == expected);
    CHECK(file.header().channels().findChannel("beauty.R")->type == Imf::FLOAT);
    CHECK(file.header().channels().findChannel("depth.Z")->type == Imf::FLOAT);
    CHECK(file.header().channels().findChannel("albedo.R")->type == Imf::HALF);

    // Beauty is the radiance the PFM holds, bit for bit (both 32-bit floats of the same frame).
    const std::vector<float> beauty = read_channels(file, {"beauty.R", "beauty.G", "beauty.B"});
    const vplkit::PfmImage hdr = vplkit::read_pfm(pfm);
    REQUIRE(hdr.width == 32);
    REQUIRE(hdr.height == 32);
    CHECK(beauty == hdr.rgb);
    // And direct + indirect (the compose pass's sum), to float rounding.
    const std::vector<float> direct = read_channels(file, {"direct.R", "direct.G", "direct.B"});
    const std::vector<float> indirect = read_channels(file, {"indirect.R", "indirect.G", "indirect.B"});
    double indirect_sum = 0.0;
    for (size_t i = 0; i < beauty.size(); ++i) {
        CHECK(std::abs(beauty[i] - (direct[i] + indirect[i])) <= 1e-5f * (1.0f + std::abs(beauty[i])));
        indirect_sum += indirect[i];
    }
    CHECK(indirect_sum > 0.0);

    // Geometry: a unit normal, a positive finite depth and an albedo in [0, 1]; elsewhere a zero
    // normal and infinite depth. The Cornell box fills most of its frame.
    const std::vector<float> normal = read_channels(file, {"normal.X", "normal.Y", "normal.Z"});
    const std::vector<float> albedo = read_channels(file, {"albedo.R", "albedo.G", "albedo.B"});
    const std::vector<float> depth = read_channels(file, {"depth.Z"});
    const std::vector<float> variance = read_channels(file, {"variance.Y"});
    size_t covered = 0;
    for (size_t p = 0; p < depth.size(); ++p) {
        const float length = std::hypot(normal[3 * p], normal[3 * p + 1], normal[3 * p + 2]);
        CAPTURE(p);
        if (std::isfinite(depth[p])) {
            ++covered;
            CHECK(depth[p] > 0.0f);
            CHECK(std::abs(length - 1.0f) < 2e-3f);
            for (int c = 0; c < 3; ++c) CHECK((albedo[3 * p + c] >= 0.0f && albedo[3 * p + c] <= 1.0f));
        } else {
            CHECK(depth[p] > 0.0f);  // +inf, not NaN
            CHECK(length == 0.0f);
        }
        CHECK(std::isfinite(variance[p]));
    }
    CHECK(covered > depth.size() / 2);

    const nlohmann::json s = nlohmann::json::parse(read_text(stats));
    CHECK(s["format"] == "vplkit stats 1");
    CHECK(s["command"] == "render");
    CHECK(s["device"]["lavapipe"] == true);
    CHECK(s["device"]["name"].get<std::string>().find("llvmpipe") != std::string::npos);
    CHECK(s["width"] == 32);
    CHECK(s["frames"] == 2);
    CHECK(s["frame_ms"].get<double>() > 0.0);
    CHECK(s["timed_frame_indices"] == nlohmann::json::array({1, 1}));
    CHECK(s["frame_gpu_ms"].size() == 2);
    // The second frame reuses the first's VPLs and trees: two plans, each stage with its reason.
    REQUIRE(s["plans"].size() == 2);
    CHECK(s["plans"][0]["frame_indices"] == nlohmann::json::array({0, 0}));
    CHECK(s["plans"][1]["reuse_vpls"] == true);
    for (const auto& stage : s["plans"][0]["stages"]) {
        CHECK(stage["runs"].is_boolean());
        CHECK(!stage["reason"].get<std::string>().empty());
    }
    std::set<std::string> timed_stages;
    for (const auto& stage : s["stage_ms"]) timed_stages.insert(stage["stage"].get<std::string>());
    CHECK(timed_stages.count("gbuffer") == 1);
    CHECK(timed_stages.count("gi hybrid") == 1);
    CHECK(timed_stages.count("denoise") == 1);
    // What frame 1 made and frame 2 reused: its own list with frame 1's time, not in the medians.
    std::set<std::string> first_only;
    for (const auto& stage : s["first_frame_only_stage_ms"]) {
        first_only.insert(stage["stage"].get<std::string>());
        CHECK(stage["ms"].get<double>() >= 0.0);
    }
    CHECK(first_only.count("vpl sort") == 1);
    CHECK(first_only.count("sst") == 1);
    CHECK(timed_stages.count("vpl sort") == 0);
    CHECK(!s["first_frame_only_pass_ms"].empty());
    CHECK(s["counters"]["vpls"].get<int>() > 0);
    CHECK(s["counters"]["gi"]["traversals"].get<int>() > 0);
    CHECK(s["firefly_moved_fraction"].is_number());
    CHECK(s["outputs"] == nlohmann::json::array({exr.string(), pfm.string()}));
}

TEST_CASE("render's EXR without indirect light or a denoiser has only the layers the frame has") {
    vplkit::test::ScratchFolder folder("render-exr-direct");
    const auto exr = folder.path / "direct.exr";
    run_vplkit("render --scene cornell --width 16 --height 16 --out \"" + (folder.path / "direct.png").string() +
                   "\" --out-hdr \"" + exr.string() + "\"",
               folder.path / "log.txt");
    Imf::InputFile file(exr.c_str());
    const std::set<std::string> expected = {"beauty.R", "beauty.G", "beauty.B", "direct.R", "direct.G",
                                            "direct.B", "albedo.R", "albedo.G", "albedo.B", "normal.X",
                                            "normal.Y", "normal.Z", "depth.Z"};
    CHECK(channel_names(file) == expected);
    CHECK(std::filesystem::exists(folder.path / "direct.png"));
}

TEST_CASE("sequence writes stats with a plan per run of frames alike and each frame's counters") {
    vplkit::test::ScratchFolder folder("sequence-stats");
    const auto stats = folder.path / "stats.json";
    run_vplkit("sequence --scene cornell --width 16 --height 16 --frames 3 --method sst --vpl-source ir --out \"" +
                   (folder.path / "frames").string() + "\" --stats \"" + stats.string() + "\"",
               folder.path / "log.txt");
    const nlohmann::json s = nlohmann::json::parse(read_text(stats));
    CHECK(s["command"] == "sequence");
    CHECK(s["frames"] == 3);
    CHECK(s["frame_ms"].get<double>() > 0.0);
    CHECK(s["timed_frame_indices"] == nlohmann::json::array({1, 2}));
    REQUIRE(s["per_frame"].size() == 3);
    CHECK(s["per_frame"][2]["frame_index"] == 2);
    CHECK(s["per_frame"][2]["counters"]["vpls"].get<int>() > 0);
    CHECK(s["per_frame"][2]["firefly_moved_fraction"].is_number());  // svgf, sequence's default
    // ir VPLs follow the seed: frames 1 and 2 reuse frame 0's, one plan for both.
    REQUIRE(s["plans"].size() == 2);
    CHECK(s["plans"][1]["frame_indices"] == nlohmann::json::array({1, 2}));
}

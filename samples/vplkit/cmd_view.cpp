// `vplkit view`: the renderer in a window. Each loop renders a frame with the current camera and
// settings (render's options set them at start), blits it into the window's left part and draws
// the panel in a column on the right (view_layout.hpp). With --screenshot the loop runs --frames
// frames and writes the last one as the window shows it: the mode tests and scripts use.

#include "budget_option.hpp"
#include "cli.hpp"
#include "cli_checks.hpp"
#include "commands.hpp"
#include "render_request.hpp"
#include "setting_flags.hpp"
#include "view_camera.hpp"
#include "view_gui.hpp"
#include "view_layout.hpp"
#include "view_panel.hpp"
#include "view_presenter.hpp"
#include "view_swapchain.hpp"
#include "view_window.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image_io.hpp"
#include "vplkit/image_metrics.hpp"
#include "vplkit/renderer.hpp"

#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace vplkit::cli {

namespace {

struct WindowSize {
    uint32_t width = 0, height = 0;
};

constexpr uint64_t kMaxWindowSide = 16384;

// "WxH" read into `size`; otherwise the problem, in the words of the checks ("expects ...").
std::string read_window_size(const std::string& text, WindowSize& size) {
    const size_t x = text.find('x');
    if (x == std::string::npos) return "expects WIDTHxHEIGHT, got '" + text + "'";
    const CLI::Validator side = whole_number_check(1, kMaxWindowSide);
    std::string width = text.substr(0, x), height = text.substr(x + 1);
    for (std::string* part : {&width, &height}) {
        const std::string problem = side(*part);
        if (!problem.empty()) return problem;
    }
    size = {uint32_t(std::stoul(width)), uint32_t(std::stoul(height))};
    return "";
}

CLI::Validator window_size_check() {
    return CLI::Validator(
        [](std::string& text) {
            WindowSize unused;
            return read_window_size(text, unused);
        },
        "", "window size");
}

// A .png in a folder that exists: checked before a window opens, not after the frames.
CLI::Validator png_path_check() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            const std::filesystem::path path = text;
            if (path.extension() != ".png") return "expects a .png file name, got '" + text + "'";
            const std::filesystem::path folder = path.parent_path().empty() ? "." : path.parent_path();
            if (!std::filesystem::is_directory(folder)) return "the folder " + folder.string() + " does not exist";
            return "";
        },
        "", "png path");
}

std::string timestamped_name() {
    const std::time_t now = std::time(nullptr);
    char text[64];
    std::strftime(text, sizeof text, "vplkit-view-%Y%m%d-%H%M%S.png", std::localtime(&now));
    return text;
}

// Key presses the loop acts on once (GLFW reports them through a callback).
struct KeyPresses {
    bool toggle_panel = false;
    bool screenshot = false;
    double scroll = 0.0;
};
KeyPresses g_presses;

void on_key(GLFWwindow* window, int key, int, int action, int) {
    if (action != GLFW_PRESS) return;
    if (key == GLFW_KEY_F1) g_presses.toggle_panel = true;
    if (key == GLFW_KEY_F12) g_presses.screenshot = true;
    if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(window, GLFW_TRUE);
}

void on_scroll(GLFWwindow*, double, double y) {
    g_presses.scroll += y;
}

// The frame with every VPL at every pixel (GiMethod::exact) for this view and VPL settings: the
// reference "compare with exact" measures against. Slow on purpose; the VPLs are the cached ones.
std::vector<float> exact_radiance(Renderer& renderer, const scene::Camera& camera, const RenderSettings& settings) {
    RenderSettings exact = settings;
    exact.method = GiMethod::exact;
    exact.denoise = DenoiseMode::off;
    exact.half_resolution_gi = false;
    exact.frame = 0;
    exact.antialias = false;  // pixel centres; the viewer's frames leave out the jitter while it is held
    exact.progress = [](uint32_t done, uint32_t total) {
        if (done == total || done % 1024 < 32) std::fprintf(stderr, "[exact gi] %u/%u VPLs\n", done, total);
    };
    std::printf("view: rendering the exact frame for comparison (the window waits)...\n");
    std::fflush(stdout);
    return renderer.render(camera, exact).radiance;
}

// The viewer's own options (render's are a RenderOptions beside them).
struct ViewOptions {
    std::optional<std::string> screenshot;
    std::optional<uint32_t> frames;
    std::optional<std::string> window;
    bool no_panel = false, compare_exact = false, no_antialias = false;
    std::optional<double> budget_ms;
};

int run_view(const CLI::App& command, const ViewOptions& o, const RenderOptions& render_options) {
    const std::optional<std::string>& screenshot = o.screenshot;
    std::optional<uint32_t> frames = o.frames;
    if (screenshot && !frames) frames = 1;
    std::optional<WindowSize> window_size;
    if (o.window) read_window_size(*o.window, window_size.emplace());  // checked when parsed
    bool show_panel = !o.no_panel;
    bool compare_exact = o.compare_exact;
    RenderRequest request = render_options.request();
    validate_render_request(request);
    filter_frames_by_default(request);

    LoadedScene loaded = load_request_scene(request);
    RenderSettings& settings = request.settings;
    // As render --frames does: jittered G-buffers averaged, here while the camera stays still
    // (a move restarts the mean).
    settings.antialias = !o.no_antialias && !settings.vpls_only;
    const scene::Scene& scene = loaded.scene;
    const VkExtent2D size = window_size ? VkExtent2D{window_size->width, window_size->height}
                                        : default_window_size({settings.width, settings.height}, show_panel);
    ViewWindow window(size.width, size.height, "vplkit view: " + loaded.described);
    request.context.instance_extensions = window.required_instance_extensions();
    request.context.device_extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    auto context = Context::create(request.context);
    const DeviceInfo& device = context->info();
    std::printf("device: %s (%s): %s\n", device.name.c_str(), device.type_name.c_str(), device.reason.c_str());
    std::printf("scene: %s: %zu triangles, %zu lights, %zu emissive triangles\n", loaded.described.c_str(),
                scene.triangle_count(), scene.lights.size(), scene.emissive_triangles.size());
    std::fflush(stdout);

    // The screenshot mode does not wait for the display's refresh.
    Swapchain swapchain(*context, window.create_surface(context->instance()), !screenshot);
    while (!swapchain.recreate(window.framebuffer_size())) window.poll_events();
    Renderer renderer(*context, scene);
    FramePresenter presenter(*context, swapchain);
    // Installed before ImGui's back end starts: it keeps them and calls them after its own, so
    // both the panel and the viewer see every key and scroll.
    glfwSetKeyCallback(window.handle(), on_key);
    glfwSetScrollCallback(window.handle(), on_scroll);
    Gui gui(*context, window.handle(), swapchain);
    ViewCamera camera(scene.camera(), loaded.target);
    ViewPanel panel;
    // --budget-ms: chosen for the start view, chosen again when the frames' times drift; a
    // setting changed in the panel ends it (the user took over).
    std::optional<BudgetPlan> budget;
    if (o.budget_ms) {
        budget.emplace(plan_budget(renderer, device, scene, camera.camera(), settings, *o.budget_ms, loaded.described,
                                   budget_fixed_by_options(command, settings)));
        settings = budget->settings;
        panel.set_budget(budget->choice.line());
    }

    uint32_t frame = 0;  // frames since the view or the settings last changed (accumulation)
    uint32_t shown = 0;
    auto last = std::chrono::steady_clock::now();
    RenderedImage image;
    RenderSettings accepted = settings;  // the last settings the renderer took
    std::vector<float> exact;            // the exact frame of this view and settings, on request
    std::optional<double> exact_error;   // the last frame's relative RMSE against it
    bool panel_changed = false;          // a setting changed in the panel: the next frame starts over
    while (!window.close_requested()) {
        window.poll_events();
        const auto now = std::chrono::steady_clock::now();
        const double seconds = std::chrono::duration<double>(now - last).count();
        last = now;
        if (g_presses.toggle_panel) show_panel = !show_panel;
        g_presses.toggle_panel = false;
        camera.zoom(g_presses.scroll);
        g_presses.scroll = 0.0;
        // After begin_frame: ImGui has seen this frame's input and knows whether the pointer is
        // over the panel.
        gui.begin_frame();
        const bool moved = camera.update(window.handle(), seconds, !gui.wants_mouse(), !gui.wants_keyboard());
        const ViewLayout layout = view_layout(swapchain.extent(), show_panel);
        const float points = 1.0f / gui.pixels_per_point();
        const PanelColumn column{float(layout.panel_area.offset.x) * points,
                                 float(layout.panel_area.extent.width) * points,
                                 float(layout.panel_area.extent.height) * points};
        const bool changed = std::exchange(panel_changed, false);
        if (moved || changed) {
            frame = 0;
            exact.clear();
        }
        if (changed && budget) {
            budget.reset();
            panel.set_budget("budget: off (a setting was changed here)");
        }
        settings.frame = frame++;
        // The exact frame is sampled at pixel centres: while it is held the frames are too, so
        // that the error measures noise and bias, not the edges anti-aliasing softens.
        RenderSettings drawn = settings;
        if (!exact.empty()) drawn.antialias = false;
        try {
            image = renderer.render(camera.camera(), drawn);
            accepted = settings;
        } catch (const Error& e) {
            if (!changed) throw;
            // A combination the renderer refuses (e.g. BRSM without a punctual light): say why
            // in the panel and go back to the last settings it took.
            panel.set_error(with_flags(e.what()));
            settings = accepted;
            frame = 0;
            continue;
        }
        panel.add_frame(image);
        if (budget) {
            double frame_ms = 0.0;
            for (const PassTiming& t : image.timings) frame_ms += t.gpu_ms;
            if (budget->drift.record(frame_ms)) {
                replan_for_budget(*budget);
                settings = apply_budget_config(settings, budget->choice.chosen.config, budget->vpl_source);
                frame = 0;
                panel.set_budget(budget->choice.line());
                std::printf("view: measured times %.2fx the calibration's: re-planned: %s\n", budget->drift.scale(),
                            budget->choice.line().c_str());
                std::fflush(stdout);
            }
        }
        if (panel.take_exact_request() || std::exchange(compare_exact, false)) {
            exact = exact_radiance(renderer, camera.camera(), settings);
            // The exact frame went through the renderer's accumulation (anti-aliasing, the
            // denoiser's history): the next frame starts them afresh.
            frame = 0;
        }
        exact_error = std::nullopt;
        if (exact.size() == image.radiance.size()) exact_error = relative_rmse(image.radiance, exact);
        panel.set_exact_error(exact_error);
        // After the frame, so that the panel shows the frame it sits beside; what it changes
        // applies from the next frame.
        panel_changed = show_panel && panel.draw(settings, image, column);

        const bool last_frame = frames && shown + 1 == *frames;
        const bool capture = (screenshot && last_frame) || g_presses.screenshot;
        WindowPixels pixels;
        auto overlay = [&](VkCommandBuffer cmd) { gui.record(cmd); };
        if (!presenter.present(image.rgba8, image.width, image.height, layout.image_area, overlay,
                               capture ? &pixels : nullptr)) {
            // The window changed size: new images, and the frame again (a screenshot too).
            while (!swapchain.recreate(window.framebuffer_size()) && !window.close_requested()) window.poll_events();
            gui.swapchain_changed(swapchain);
            continue;
        }
        ++shown;
        if (capture) {
            const std::filesystem::path path = screenshot && last_frame ? *screenshot : timestamped_name();
            write_png(path, pixels.width, pixels.height, pixels.rgba);
            std::printf("wrote %s (%ux%u, the frame %ux%u)\n", path.string().c_str(), pixels.width, pixels.height,
                        image.width, image.height);
            std::fflush(stdout);
            g_presses.screenshot = false;
        }
        if (last_frame) break;
    }
    if (exact_error) std::printf("relative RMSE against the exact frame: %.5f\n", *exact_error);
    if (image.non_finite_pixels > 0) {
        std::printf("warning: %u pixels of the last frame were NaN or infinite (magenta)\n", image.non_finite_pixels);
    }
    if (context->validation_message_count() > 0) {
        std::fprintf(stderr, "vplkit: view: %llu validation messages (see above)\n",
                     (unsigned long long)context->validation_message_count());
        return 1;
    }
    return 0;
}

}  // namespace

void add_view(CLI::App& vplkit, Runners& runners) {
    CLI::App* view = add_command(
        vplkit, "view",
        "a window: the scene rendered live, a panel to switch methods and settings; --screenshot for scripts",
        "A window showing the renderer's frames, with a panel to change the method and its settings while it "
        "runs (the planner's reasons and per-stage GPU times alongside). Takes render's options: they set the "
        "first frame's scene, size, method and settings. The panel sits in a column right of the frame "
        "(F1 hides it and the frame takes the whole window); anti-aliasing accumulates while the camera is "
        "still.\n"
        "  mouse: left-drag orbits the target, right-drag looks around, wheel zooms\n"
        "  keys: W A S D move, Q E down and up, Shift faster; F1 shows or hides the panel; F12 writes the "
        "window to vplkit-view-<time>.png in the working folder; Esc quits");
    auto o = std::make_shared<ViewOptions>();
    view->add_option_function<std::string>(
            "--screenshot", [o](const std::string& v) { o->screenshot = v; },
            "render --frames frames, write the window's image (the panel's column too, unless hidden) to "
            "FILE.png, exit")
        ->check(png_path_check())
        ->option_text("FILE.png")
        ->group("view");
    whole_number(view->add_option_function<uint32_t>(
                     "--frames", [o](uint32_t v) { o->frames = v; },
                     "frames before the screenshot (default 1), or before closing without one"),
                 "N", 1, 100000)
        ->group("view");
    view->add_option_function<std::string>(
            "--window", [o](const std::string& v) { o->window = v; },
            "the window's size, the panel's column included (default: the frame's size, plus a column of " +
                std::to_string(kPanelColumnWidth) + " for the panel, at least " + std::to_string(kPanelMinHeight) +
                " high); the frame is scaled to fit the part left of the panel")
        ->check(window_size_check())
        ->option_text("WxH")
        ->group("view");
    view->add_flag("--no-panel", o->no_panel,
                   "start with the panel hidden (F1 shows it): the window is the frame's size, the frame fills it")
        ->group("view");
    view->add_flag("--no-antialias", o->no_antialias,
                   "start with anti-aliasing off (the panel's checkbox): every frame at the pixel centres")
        ->group("view");
    view->add_flag("--compare-exact", o->compare_exact,
                   "render the exact frame (every VPL at every pixel) once at start and show each frame's "
                   "relative RMSE against it (the panel's button does the same); while it is held, frames are "
                   "drawn at its pixel centres (anti-aliasing pauses), so the error is the method's own")
        ->group("view");
    add_budget_option(*view, o->budget_ms,
                      "; chosen for the start view (shown in the panel), chosen again when the median of the last 5 "
                      "frames' GPU time leaves 1/1.15..1.15 of the prediction, ended by a change in the panel")
        ->group("view");
    auto render_options = std::make_shared<RenderOptions>(*view);
    // Frame after frame on a still or moving camera: what the filter is for, as in sequence.
    view->get_option("--denoise")->default_str("svgf for a sampled method, off for direct and exact");
    runners.push_back({view, [view, o, render_options] { return run_view(*view, *o, *render_options); }});
}

}  // namespace vplkit::cli

// `vplkit view`: the renderer in a window. Each loop renders a frame with the current camera and
// settings (render's options set them at start), blits it into the window and draws the panel on
// top. With --screenshot the loop runs --frames frames and writes the last one as the window shows
// it: the mode tests and scripts use.

#include "cli.hpp"
#include "commands.hpp"
#include "render_request.hpp"
#include "setting_flags.hpp"
#include "view_camera.hpp"
#include "view_gui.hpp"
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
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace vplkit::cli {

const char* const kViewUsage =
    "usage: vplkit view [render's scene and method options] [--screenshot FILE.png [--frames N]]\n"
    "                   [--window WxH] [--no-panel] [--compare-exact]\n"
    "\n"
    "A window showing the renderer's frames, with a panel to change the method and its settings\n"
    "while it runs (the planner's reasons and per-stage GPU times alongside).\n"
    "  mouse: left-drag orbits the target, right-drag looks around, wheel zooms\n"
    "  keys:  W A S D move, Q E down and up, Shift faster; F1 shows or hides the panel;\n"
    "         F12 writes the window to vplkit-view-<time>.png in the working folder; Esc quits\n"
    "\n"
    "options (besides render's --scene, --method, --width, --height, ...; see 'vplkit render --help'):\n"
    "  --screenshot FILE.png  render --frames frames, write the window's image to FILE.png, exit\n"
    "  --frames N             frames before the screenshot (default 1), or before closing without one\n"
    "  --window WxH           the window's size (default: the frame's size); the frame is scaled to fit\n"
    "  --no-panel             start with the panel hidden\n"
    "  --compare-exact        render the exact frame (every VPL at every pixel) once at start and show\n"
    "                         each frame's relative RMSE against it (the panel's button does the same)\n";

namespace {

struct WindowSize {
    uint32_t width = 0, height = 0;
};

WindowSize parse_window_size(const std::string& text) {
    const size_t x = text.find('x');
    if (x == std::string::npos) throw UsageError("--window expects WIDTHxHEIGHT, got '" + text + "'");
    return {parse_whole_number("--window", text.substr(0, x), 16384),
            parse_whole_number("--window", text.substr(x + 1), 16384)};
}

void check_png_path(const std::filesystem::path& path) {
    if (path.extension() != ".png") {
        throw UsageError("--screenshot expects a .png file name, got '" + path.string() + "'");
    }
    const std::filesystem::path folder = path.parent_path().empty() ? "." : path.parent_path();
    if (!std::filesystem::is_directory(folder)) {
        throw UsageError("--screenshot: the folder " + folder.string() + " does not exist");
    }
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
    exact.progress = [](uint32_t done, uint32_t total) {
        if (done == total || done % 1024 < 32) std::fprintf(stderr, "[exact gi] %u/%u VPLs\n", done, total);
    };
    std::printf("view: rendering the exact frame for comparison (the window waits)...\n");
    std::fflush(stdout);
    return renderer.render(camera, exact).radiance;
}

}  // namespace

int run_view(Args& args) {
    const std::optional<std::string> screenshot = args.value("--screenshot");
    std::optional<uint32_t> frames;
    if (auto text = args.value("--frames")) frames = parse_whole_number("--frames", *text, 100000);
    std::optional<WindowSize> window_size;
    if (auto text = args.value("--window")) window_size = parse_window_size(*text);
    bool show_panel = !args.flag("--no-panel");
    bool compare_exact = args.flag("--compare-exact");
    RenderRequest request = parse_render_request(args);
    args.finish();
    validate_render_request(request);
    if (screenshot) check_png_path(*screenshot);
    if (screenshot && !frames) frames = 1;

    LoadedScene loaded = load_request_scene(request);
    RenderSettings& settings = request.settings;
    const scene::Scene& scene = loaded.scene;
    const WindowSize size = window_size.value_or(WindowSize{settings.width, settings.height});
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

    uint32_t frame = 0;  // frames since the view or the settings last changed (accumulation)
    uint32_t shown = 0;
    auto last = std::chrono::steady_clock::now();
    RenderedImage image;
    RenderSettings accepted = settings;  // the last settings the renderer took
    std::vector<float> exact;            // the exact frame of this view and settings, on request
    std::optional<double> exact_error;   // the last frame's relative RMSE against it
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
        const bool changed = show_panel && panel.draw(settings, image);
        if (moved || changed) {
            frame = 0;
            exact.clear();
        }
        settings.frame = frame++;
        try {
            image = renderer.render(camera.camera(), settings);
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
        if (panel.take_exact_request() || std::exchange(compare_exact, false)) {
            exact = exact_radiance(renderer, camera.camera(), settings);
            // The exact frame went through the renderer's accumulation (anti-aliasing, the
            // denoiser's history): the next frame starts them afresh.
            frame = 0;
        }
        exact_error = std::nullopt;
        if (exact.size() == image.radiance.size()) exact_error = relative_rmse(image.radiance, exact);
        panel.set_exact_error(exact_error);

        const bool last_frame = frames && shown + 1 == *frames;
        const bool capture = (screenshot && last_frame) || g_presses.screenshot;
        WindowPixels pixels;
        auto overlay = [&](VkCommandBuffer cmd) { gui.record(cmd); };
        if (!presenter.present(image.rgba8, image.width, image.height, overlay, capture ? &pixels : nullptr)) {
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

}  // namespace vplkit::cli

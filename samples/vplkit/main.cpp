// vplkit: the command-line program. main() only dispatches: each subcommand is a file of its own
// (cmd_<name>.cpp) and one line in kCommands.

#include "cli.hpp"
#include "commands.hpp"
#include "setting_flags.hpp"

#include "vplkit/error.hpp"

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

using vplkit::cli::Args;
using vplkit::cli::Command;
using vplkit::cli::UsageError;

// A command's usage that is a fixed text.
template <const char* const* text>
std::string fixed_usage() {
    return *text;
}

const Command kCommands[] = {
    {"info", "list the Vulkan devices, the one vplkit picks and why, and its features",
     fixed_usage<&vplkit::cli::kInfoUsage>, vplkit::cli::run_info},
    {"render", "render a scene (set-up name or glTF file) to a PNG, with per-stage GPU times",
     vplkit::cli::render_usage, vplkit::cli::run_render},
    {"plan", "the stages a frame of a scene would run and why (render's options; no device work)",
     fixed_usage<&vplkit::cli::kPlanUsage>, vplkit::cli::run_plan},
    {"bench", "GPU timings of the kit's stages (sort, tree, bvh; gi --scene NAME: accuracy vs time of every method)",
     vplkit::cli::bench_usage, vplkit::cli::run_bench},
    {"compare", "error of a PFM or PNG image against a reference: RMSE, relative RMSE, relMSE, SSIM; difference PNG",
     fixed_usage<&vplkit::cli::kCompareUsage>, vplkit::cli::run_compare},
    {"sequence", "frames along a camera path (orbit or keyframes); --reference: temporal error |E|, |E'| vs exact",
     fixed_usage<&vplkit::cli::kSequenceUsage>, vplkit::cli::run_sequence},
    {"view", "a window: the scene rendered live, a panel to switch methods and settings; --screenshot for scripts",
     fixed_usage<&vplkit::cli::kViewUsage>, vplkit::cli::run_view},
};

void print_usage(std::FILE* out) {
    std::fprintf(out, "usage: vplkit <command> [options]\n\ncommands:\n");
    for (const Command& c : kCommands) std::fprintf(out, "  %-8s %s\n", c.name, c.summary);
    std::fprintf(
        out,
        "\n'vplkit <command> --help' shows a command's options.\n"
        "environment: VPLKIT_DEVICE=auto|gpu|cpu|<index>|<name part> picks the device when no --device is given\n");
}

const Command* find_command(const std::string& name) {
    for (const Command& c : kCommands) {
        if (name == c.name) return &c;
    }
    return nullptr;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty()) {
        std::fprintf(stderr, "vplkit: no command given\n");
        print_usage(stderr);
        return 2;
    }
    const std::string name = args.front();
    if (name == "--help" || name == "-h" || name == "help") {
        print_usage(stdout);
        return 0;
    }
    const Command* command = find_command(name);
    if (!command) {
        std::fprintf(stderr, "vplkit: unknown %s '%s'\n", name.rfind('-', 0) == 0 ? "option" : "command", name.c_str());
        print_usage(stderr);
        return 2;
    }
    Args command_args(name, std::vector<std::string>(args.begin() + 1, args.end()));
    try {
        if (command_args.flag("--help", "-h")) {
            std::fputs(command->usage().c_str(), stdout);
            return 0;
        }
        return command->run(command_args);
    } catch (const UsageError& e) {
        std::fprintf(stderr, "vplkit: %s\n", vplkit::cli::with_flags(e.what()).c_str());
        std::fputs(command->usage().c_str(), stderr);
        return 2;
    } catch (const std::exception& e) {
        // Runtime errors already start with "vplkit: "; the settings they name become flags.
        const std::string text = vplkit::cli::with_flags(e.what());
        std::fprintf(stderr, "%s%s\n", text.rfind("vplkit: ", 0) == 0 ? "" : "vplkit: ", text.c_str());
        return 1;
    }
}

// vplkit: the command-line program. main() only dispatches: each subcommand is a file of its own
// (cmd_<name>.cpp) that declares its options through CLI11 (commands.hpp); the help pages are
// generated from those declarations.

#include "cli.hpp"
#include "cli_app.hpp"
#include "commands.hpp"
#include "setting_flags.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

using vplkit::cli::Runner;
using vplkit::cli::Runners;
using vplkit::cli::UsageError;

// The subcommand chosen: the deepest one parsed (e.g. bench, then gi).
const CLI::App* chosen_command(const CLI::App& app) {
    const CLI::App* at = &app;
    while (!at->get_subcommands().empty()) at = at->get_subcommands().front();
    return at;
}

void print_usage_hint(const CLI::App& app, const CLI::App* command) {
    if (command == &app) {
        std::fprintf(stderr, "usage: vplkit <command> [options]; 'vplkit --help' lists the commands\n");
    } else {
        const std::string path = vplkit::cli::command_path(*command);
        std::fprintf(stderr, "usage: vplkit %s [options]; 'vplkit %s --help' lists them\n", path.c_str(), path.c_str());
    }
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    CLI::App app("vplkit: virtual point lights on Vulkan: render, plan, measure and compare global illumination.",
                 "vplkit");
    vplkit::cli::configure_app(app);
    app.allow_extras();  // an unknown option is reported as vplkit words it
    Runners runners;
    vplkit::cli::add_info(app, runners);
    vplkit::cli::add_render(app, runners);
    vplkit::cli::add_plan(app, runners);
    vplkit::cli::add_bench(app, runners);
    vplkit::cli::add_compare(app, runners);
    vplkit::cli::add_sequence(app, runners);
    vplkit::cli::add_view(app, runners);
    // Set after the commands, which would inherit it.
    app.footer(
        "'vplkit <command> --help' shows a command's options.\n"
        "environment: VPLKIT_DEVICE=auto|gpu|cpu|<index>|<name part> picks the device (unless --device)");

    if (args.empty()) {
        std::fprintf(stderr, "vplkit: no command given\n%s", app.help().c_str());
        return 2;
    }
    if (args.front() == "help") args.front() = "--help";
    const auto& commands = app.get_subcommands({});
    const bool known =
        std::any_of(commands.begin(), commands.end(), [&](const CLI::App* c) { return c->get_name() == args.front(); });
    if (!known && args.front().rfind('-', 0) != 0) {
        std::fprintf(stderr, "vplkit: unknown command '%s'\n", args.front().c_str());
        print_usage_hint(app, &app);
        return 2;
    }
    // Options before the benchmark's name are the benchmark's (`vplkit bench --scene S bvh`); with no
    // name, they are the GI bench's (`vplkit bench --scene cornell --quick`: README's short form).
    if (args.size() > 1 && args.front() == "bench" && args[1].rfind('-', 0) == 0 && args[1] != "--help" &&
        args[1] != "-h") {
        const auto benchmarks = static_cast<const CLI::App*>(app.get_subcommand("bench"))->get_subcommands({});
        const auto name = std::find_if(args.begin() + 2, args.end(), [&](const std::string& a) {
            return std::any_of(benchmarks.begin(), benchmarks.end(),
                               [&](const CLI::App* b) { return b->get_name() == a; });
        });
        if (name == args.end()) {
            args.insert(args.begin() + 1, "gi");
        } else {
            std::rotate(args.begin() + 1, name, name + 1);
        }
    }

    const CLI::App* command = &app;
    try {
        std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
        try {
            app.parse(reversed);
        } catch (const CLI::CallForHelp& e) {
            return app.exit(e);
        } catch (const CLI::ParseError& e) {
            throw UsageError(vplkit::cli::parse_error_text(e));
        }
        command = chosen_command(app);
        if (command == &app) {
            vplkit::cli::check_parsed(app);
            throw UsageError("no command given");
        }
        const auto runner =
            std::find_if(runners.begin(), runners.end(), [&](const Runner& r) { return r.app == command; });
        if (runner == runners.end()) throw UsageError("no command given");
        if (!runner->reads_leftovers) vplkit::cli::check_parsed(*command);
        // What was left before the command's name (`vplkit --x render`) is no one's.
        for (const CLI::App* above = command->get_parent(); above; above = above->get_parent()) {
            vplkit::cli::check_parsed(*above);
        }
        return runner->run();
    } catch (const UsageError& e) {
        if (command == &app) command = chosen_command(app);
        std::fprintf(stderr, "vplkit: %s\n", vplkit::cli::with_flags(e.what()).c_str());
        print_usage_hint(app, command);
        return 2;
    } catch (const std::exception& e) {
        // Runtime errors already start with "vplkit: "; the settings they name become flags.
        const std::string text = vplkit::cli::with_flags(e.what());
        std::fprintf(stderr, "%s%s\n", text.rfind("vplkit: ", 0) == 0 ? "" : "vplkit: ", text.c_str());
        return 1;
    }
}

#pragma once
// The command line's frame, through CLI11: each subcommand declares its options once (name, help,
// check) and the help pages are generated from those declarations. Here: the formatter that wraps
// them, the settings every subcommand shares, and the checks after parsing that CLI11 leaves to us
// (an unknown option or an option given twice is one clear line, exit 2).

#include "cli.hpp"

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace vplkit::cli {

// A subcommand and what runs it when it is the one chosen (returns the exit code: 0 or 1; a
// UsageError means 2).
struct Runner {
    const CLI::App* app;
    std::function<int()> run;
    bool reads_leftovers = false;  // looks at app->remaining() itself (bench's name)
};
using Runners = std::vector<Runner>;

// vplkit's top-level app: the formatter, and every option refused when given twice.
void configure_app(CLI::App& app);

// A subcommand of `parent`. `summary` is its line in the parent's list; `about` (paragraphs,
// wrapped) opens its own --help.
CLI::App* add_command(CLI::App& parent, const std::string& name, const std::string& summary,
                      const std::string& about = "");

// "bench gi" for that subcommand (the program's name left out).
std::string command_path(const CLI::App& command);

// After parsing: an unknown option, an unexpected argument or an option given more than once
// (those declared with ->take_all() excepted) is a UsageError naming it.
void check_parsed(const CLI::App& command);

// A CLI11 parse error as the one line vplkit prints ("--spp expects ..., got '0'").
std::string parse_error_text(const CLI::ParseError& error);

}  // namespace vplkit::cli

#pragma once
// The small command-line toolkit the subcommands share: the usage error that makes the program
// exit 2, the text helpers, and an argument cursor for a command that reads its arguments itself
// (view; the others declare theirs through CLI11, cli_app.hpp).

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace vplkit::cli {

// A mistake on the command line: main prints "vplkit: <message>", the usage, and exits 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// A subcommand's arguments. Take what the command understands, then call finish(): anything
// left over is an unknown option or a surplus argument, reported as a UsageError.
class Args {
public:
    Args(std::string command, std::vector<std::string> args) : command_(std::move(command)), args_(std::move(args)) {}

    // --name (or -short): true when present.
    bool flag(std::string_view name, std::string_view short_name = {});
    // --name VALUE or --name=VALUE.
    std::optional<std::string> value(std::string_view name);
    // The next argument that is not an option.
    std::optional<std::string> positional();
    // Refuses what is left: an option already read ("given more than once"; the options read in
    // a loop, such as --sun, take every occurrence), an unknown option, or an extra argument.
    void finish() const;

    const std::string& command() const { return command_; }
    // Every argument not read yet, taken (for a parser of the rest, e.g. parse_render_request).
    std::vector<std::string> take_rest() { return std::exchange(args_, {}); }

private:
    std::string command_;
    std::vector<std::string> args_;
    std::vector<std::string> read_;  // the options flag() and value() found
};

// A whole number from 1 to max, or a UsageError naming the option and the text.
uint32_t parse_whole_number(const std::string& option, const std::string& text, uint64_t max);
// Comma-separated whole numbers, each from 1 to max (at least one).
std::vector<uint32_t> parse_whole_number_list(const std::string& option, const std::string& text, uint64_t max);

// `text` (words and single spaces) in lines of at most `width` characters, the first starting at
// `first_column`, the others indented by `indent` (usage texts).
std::string wrapped(const std::string& text, size_t first_column, size_t indent, size_t width = 100);

}  // namespace vplkit::cli

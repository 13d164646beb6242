#pragma once
// The small command-line toolkit the subcommands share: the usage error that makes the program
// exit 2 and the text helpers (the options themselves are declared through CLI11, cli_app.hpp).

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace vplkit::cli {

// A mistake on the command line: main prints "vplkit: <message>", the usage, and exits 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Comma-separated whole numbers, each from 1 to max (at least one), or a UsageError naming the
// option and the text.
std::vector<uint32_t> parse_whole_number_list(const std::string& option, const std::string& text, uint64_t max);

// `text` (words and single spaces) in lines of at most `width` characters, the first starting at
// `first_column`, the others indented by `indent` (usage texts).
std::string wrapped(const std::string& text, size_t first_column, size_t indent, size_t width = 100);

}  // namespace vplkit::cli

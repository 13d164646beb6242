#pragma once
// The checks the command line's options carry (CLI11 validators), each with the wording of one
// clear error: "expects a whole number from 1 to 64, got '0'" (CLI11 prefixes the option's name).
// Declaring an option with one of the helpers sets its check and the value's shape in --help
// ("N, 1..64"), so the help and the parser read the same declaration.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace vplkit::cli {

// A whole number from `min` to `max` (decimal digits only).
CLI::Validator whole_number_check(uint64_t min, uint64_t max);
// The option takes a whole number from `min` to `max`; `name` is the value's name in the help ("N").
CLI::Option* whole_number(CLI::Option* option, const std::string& name, uint64_t min, uint64_t max);
// Comma-separated whole numbers, each from 1 to `max` (at least one).
CLI::Option* whole_number_list(CLI::Option* option, const std::string& name, uint64_t max);

// Where a real number may lie; a bound is open (excluded) or closed.
struct NumberRange {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool min_open = false;
    bool max_open = false;
    std::string what;  // the error's noun ("a finite number of seconds"); "" = from the bounds

    static NumberRange any() { return {}; }
    static NumberRange above(double v) { return {v, std::numeric_limits<double>::infinity(), true, false, {}}; }
    static NumberRange at_least(double v) { return {v, std::numeric_limits<double>::infinity(), false, false, {}}; }
    static NumberRange from(double lo, double hi) { return {lo, hi, false, false, {}}; }
    static NumberRange between(double lo, double hi) { return {lo, hi, true, true, {}}; }
};
// A finite number in `range`.
CLI::Validator number_check(const NumberRange& range);
// The option takes a finite number in `range`; `name` is the value's name in the help ("MU").
CLI::Option* number(CLI::Option* option, const std::string& name, const NumberRange& range);

// One of `names` (CLI::IsMember), "expects a, b or c, got 'x'".
CLI::Validator one_of_check(const std::vector<std::string>& names);
// The option takes one of `names`; the help names the value by listing them ("auto|on|off").
CLI::Option* one_of(CLI::Option* option, const std::vector<std::string>& names);

// Comma-separated names, each one of `names`: "expects a comma-separated list of a, b, c, got 'x'
// in 'a,x'"; the help lists them.
CLI::Validator name_list_check(const std::vector<std::string>& names);
CLI::Option* name_list(CLI::Option* option, const std::vector<std::string>& names);
// The names of a list `text` (split at commas; checked by name_list_check).
std::vector<std::string> split_names(const std::string& text);

// "a, b or c".
std::string spoken_list(const std::vector<std::string>& names);

}  // namespace vplkit::cli

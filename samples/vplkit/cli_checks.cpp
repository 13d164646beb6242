#include "cli_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace vplkit::cli {

namespace {

// The whole text as a finite number, or NaN.
double finite_or_nan(const std::string& text) {
    if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return NAN;
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || !std::isfinite(value)) return NAN;
    return value;
}

// 1, 0.5, 1e+06: the shortest form that reads back.
std::string number_text(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

std::string range_noun(const NumberRange& r) {
    if (!r.what.empty()) return r.what;
    const bool low = std::isfinite(r.min), high = std::isfinite(r.max);
    if (low && high && !r.min_open && !r.max_open) {
        return "a number from " + number_text(r.min) + " to " + number_text(r.max);
    }
    if (low && high) return "a number above " + number_text(r.min) + " and below " + number_text(r.max);
    if (low && r.min_open) return r.min == 0.0 ? "a positive number" : "a number above " + number_text(r.min);
    if (low) return "a number >= " + number_text(r.min);
    if (high) return "a number <= " + number_text(r.max);
    return "a number";
}

std::string range_shape(const NumberRange& r) {
    const bool low = std::isfinite(r.min), high = std::isfinite(r.max);
    if (low && high) {
        return (r.min_open ? "(" : "[") + number_text(r.min) + ", " + number_text(r.max) + (r.max_open ? ")" : "]");
    }
    if (low) return (r.min_open ? "> " : ">= ") + number_text(r.min);
    if (high) return (r.max_open ? "< " : "<= ") + number_text(r.max);
    return "";
}

}  // namespace

std::string spoken_list(const std::vector<std::string>& names) {
    std::string text;
    for (size_t i = 0; i < names.size(); ++i) {
        text += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    }
    return text;
}

CLI::Validator whole_number_check(uint64_t min, uint64_t max) {
    const CLI::Validator in_range = CLI::Range(min, max);
    return CLI::Validator(
        [min, max, in_range](std::string& text) -> std::string {
            const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
            std::string copy = text;
            if (digits && text.size() <= 19 && in_range(copy).empty()) return "";
            return "expects a whole number from " + std::to_string(min) + " to " + std::to_string(max) + ", got '" +
                   text + "'";
        },
        "", "whole number");
}

CLI::Option* whole_number(CLI::Option* option, const std::string& name, uint64_t min, uint64_t max) {
    return option->check(whole_number_check(min, max))
        ->option_text(name + ", " + std::to_string(min) + ".." + std::to_string(max));
}

CLI::Option* whole_number_list(CLI::Option* option, const std::string& name, uint64_t max) {
    const CLI::Validator each = whole_number_check(1, max);
    option->check(CLI::Validator(
        [each, max](std::string& text) -> std::string {
            std::stringstream items(text);
            std::string item;
            bool any = false;
            while (std::getline(items, item, ',')) {
                any = true;
                const std::string problem = each(item);
                if (!problem.empty()) return problem;
            }
            return any ? "" : "needs at least one number from 1 to " + std::to_string(max);
        },
        "", "whole numbers"));
    return option->option_text(name + ",... each 1.." + std::to_string(max));
}

CLI::Validator number_check(const NumberRange& range) {
    return CLI::Validator(
        [range](std::string& text) -> std::string {
            const double v = finite_or_nan(text);
            const bool above_min = range.min_open ? v > range.min : v >= range.min;
            const bool below_max = range.max_open ? v < range.max : v <= range.max;
            if (std::isfinite(v) && above_min && below_max) return "";
            return "expects " + range_noun(range) + ", got '" + text + "'";
        },
        "", "number");
}

CLI::Option* number(CLI::Option* option, const std::string& name, const NumberRange& range) {
    const std::string shape = range_shape(range);
    return option->check(number_check(range))->option_text(shape.empty() ? name : name + ", " + shape);
}

CLI::Validator one_of_check(const std::vector<std::string>& names) {
    const CLI::Validator member = CLI::IsMember(names);
    return CLI::Validator(
        [member, names](std::string& text) -> std::string {
            std::string copy = text;
            if (member(copy).empty()) return "";
            return "expects " + spoken_list(names) + ", got '" + text + "'";
        },
        "", "one of");
}

CLI::Option* one_of(CLI::Option* option, const std::vector<std::string>& names) {
    std::string shape;
    for (const std::string& n : names) shape += (shape.empty() ? "" : "|") + n;
    return option->check(one_of_check(names))->option_text(shape);
}

std::vector<std::string> split_names(const std::string& text) {
    std::vector<std::string> names;
    size_t start = 0;
    while (start <= text.size()) {
        const size_t comma = std::min(text.find(',', start), text.size());
        names.push_back(text.substr(start, comma - start));
        start = comma + 1;
    }
    return names;
}

CLI::Validator name_list_check(const std::vector<std::string>& names) {
    return CLI::Validator(
        [names](std::string& text) -> std::string {
            for (const std::string& name : split_names(text)) {
                if (std::find(names.begin(), names.end(), name) == names.end()) {
                    std::string all;
                    for (const std::string& n : names) all += (all.empty() ? "" : ", ") + n;
                    return "expects a comma-separated list of " + all + ", got '" + name + "' in '" + text + "'";
                }
            }
            return "";
        },
        "", "names");
}

CLI::Option* name_list(CLI::Option* option, const std::vector<std::string>& names) {
    std::string shape;
    for (const std::string& n : names) shape += (shape.empty() ? "" : ",") + n;
    return option->check(name_list_check(names))->option_text("LIST of " + shape);
}

}  // namespace vplkit::cli

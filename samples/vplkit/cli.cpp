#include "cli.hpp"

#include <algorithm>
#include <sstream>

namespace vplkit::cli {

namespace {

// A whole number from 1 to max, or a UsageError naming the option and the text.
uint32_t parse_whole_number(const std::string& option, const std::string& text, uint64_t max) {
    size_t used = 0;
    unsigned long long value = 0;
    try {
        value = std::stoull(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (text.empty() || used != text.size() || text[0] == '-' || text[0] == '+' || value == 0 || value > max) {
        throw UsageError(option + " expects a whole number from 1 to " + std::to_string(max) + ", got '" + text + "'");
    }
    return uint32_t(value);
}

}  // namespace

std::vector<uint32_t> parse_whole_number_list(const std::string& option, const std::string& text, uint64_t max) {
    std::vector<uint32_t> values;
    std::stringstream stream(text);
    std::string item;
    while (std::getline(stream, item, ',')) values.push_back(parse_whole_number(option, item, max));
    if (values.empty()) throw UsageError(option + " needs at least one number");
    return values;
}

std::string wrapped(const std::string& text, size_t first_column, size_t indent, size_t width) {
    std::string out;
    size_t column = first_column;
    bool line_empty = true;
    size_t start = 0;
    while (start < text.size()) {
        const size_t space = std::min(text.find(' ', start), text.size());
        const std::string word = text.substr(start, space - start);
        if (!line_empty && column + 1 + word.size() > width) {
            out += "\n" + std::string(indent, ' ');
            column = indent;
        } else if (!line_empty) {
            out += ' ';
            ++column;
        }
        line_empty = false;
        out += word;
        column += word.size();
        start = space + 1;
    }
    return out;
}

}  // namespace vplkit::cli

#include "cli.hpp"

#include <algorithm>
#include <sstream>

namespace vplkit::cli {

bool Args::flag(std::string_view name, std::string_view short_name) {
    for (auto it = args_.begin(); it != args_.end(); ++it) {
        if (*it == name || (!short_name.empty() && *it == short_name)) {
            args_.erase(it);
            read_.emplace_back(name);
            if (!short_name.empty()) read_.emplace_back(short_name);
            return true;
        }
    }
    return false;
}

std::optional<std::string> Args::value(std::string_view name) {
    const std::string prefix = std::string(name) + "=";
    for (auto it = args_.begin(); it != args_.end(); ++it) {
        if (it->rfind(prefix, 0) == 0) {
            std::string v = it->substr(prefix.size());
            args_.erase(it);
            read_.emplace_back(name);
            return v;
        }
        if (*it == name) {
            if (it + 1 == args_.end()) throw UsageError("option " + std::string(name) + " needs a value");
            std::string v = *(it + 1);
            args_.erase(it, it + 2);
            read_.emplace_back(name);
            return v;
        }
    }
    return std::nullopt;
}

std::optional<std::string> Args::positional() {
    for (auto it = args_.begin(); it != args_.end(); ++it) {
        if (it->empty() || (*it)[0] != '-' || *it == "-") {
            std::string v = *it;
            args_.erase(it);
            return v;
        }
    }
    return std::nullopt;
}

void Args::finish() const {
    if (args_.empty()) return;
    const std::string& first = args_.front();
    const std::string name = first.substr(0, first.find('='));
    if (std::find(read_.begin(), read_.end(), name) != read_.end()) {
        throw UsageError("option '" + name + "' given more than once for '" + command_ + "'");
    }
    if (!first.empty() && first[0] == '-') throw UsageError("unknown option '" + first + "' for '" + command_ + "'");
    throw UsageError("unexpected argument '" + first + "' for '" + command_ + "'");
}

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

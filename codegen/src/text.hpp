// Small helpers to write C++ text that reads as if typed by hand: aligned trailing comments.
#pragma once

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace vplkit::codegen {

// Lines of code with optional trailing comments, rendered with the comments in one column.
class CommentedLines {
public:
    void add(std::string code, std::string comment = {}) { rows_.emplace_back(std::move(code), std::move(comment)); }
    bool empty() const { return rows_.empty(); }

    std::string render(const std::string& indent) const {
        size_t width = 0;
        for (const auto& [code, comment] : rows_) {
            if (!comment.empty()) width = std::max(width, code.size());
        }
        std::string out;
        for (const auto& [code, comment] : rows_) {
            out += indent + code;
            if (!comment.empty()) out += std::string(width - code.size(), ' ') + "  // " + comment;
            out += "\n";
        }
        return out;
    }

private:
    std::vector<std::pair<std::string, std::string>> rows_;
};

}  // namespace vplkit::codegen

#include "cli_app.hpp"

#include <algorithm>
#include <regex>
#include <sstream>

namespace vplkit::cli {

namespace {

constexpr size_t kHelpWidth = 100;
constexpr size_t kOptionColumn = 34;

// Each line of `text` wrapped at `width` (no indent: CLI11 indents the lines it is given).
std::string wrap_lines(const std::string& text, size_t width) {
    std::string out;
    std::stringstream lines(text);
    std::string line;
    bool first = true;
    while (std::getline(lines, line)) {
        // An indented line (a list item) keeps its indent, its continuation two more.
        const size_t indent = std::min(line.find_first_not_of(' '), line.size());
        const size_t more = indent > 0 ? indent + 2 : 0;
        out += (first ? "" : "\n") + line.substr(0, indent) +
               (indent == line.size() ? "" : wrapped(line.substr(indent), indent, more, width));
        first = false;
    }
    return out;
}

class Formatter : public CLI::Formatter {
public:
    Formatter() {
        column_width(kOptionColumn);
        label("Subcommands", "commands");
        label("Usage", "usage");
        label("Positionals", "arguments");
        label("OPTIONS", "options");
        label("SUBCOMMAND", "command");
    }
    // The option text alone (the helpers in cli_checks.hpp put the range in it); the default goes
    // into the description.
    std::string make_option_opts(const CLI::Option* option) const override {
        if (option->get_positional()) return "";
        if (!option->get_option_text().empty()) return " " + option->get_option_text();
        if (option->get_type_size() == 0) return "";
        std::string text = " " + option->get_type_name();
        if (option->get_multi_option_policy() == CLI::MultiOptionPolicy::TakeAll) text += " (repeatable)";
        return text;
    }
    std::string make_option_desc(const CLI::Option* option) const override {
        std::string text = option->get_description();
        if (!option->get_default_str().empty()) text += " (default " + option->get_default_str() + ")";
        return wrap_lines(text, kHelpWidth - kOptionColumn);
    }
    std::string make_subcommand(const CLI::App* command) const override {
        const std::string& about = command->get_description();
        std::stringstream out;
        CLI::detail::format_help(out, command->get_name(), about.substr(0, about.find('\n')), 12);
        return out.str();
    }
    // One blank line between the usage line, the arguments and each group of options (CLI11
    // separates groups twice: make_groups adds one and its make_group another).
    std::string make_group(std::string group, bool is_positional,
                           std::vector<const CLI::Option*> options) const override {
        return CLI::Formatter::make_group(group, is_positional, options).substr(1);
    }
    std::string make_usage(const CLI::App* command, std::string name) const override {
        return CLI::Formatter::make_usage(command, name) + "\n";
    }
    std::string make_positionals(const CLI::App* command) const override {
        const std::string text = CLI::Formatter::make_positionals(command);
        return text.empty() ? text : text + "\n";
    }
    std::string make_description(const CLI::App* command) const override {
        const std::string& about = command->get_description();
        return about.empty() ? "" : wrap_lines(about, kHelpWidth) + "\n\n";
    }
    std::string make_footer(const CLI::App* command) const override {
        const std::string footer = command->get_footer();
        return footer.empty() ? "" : wrap_lines(footer, kHelpWidth) + "\n";
    }
};

}  // namespace

void configure_app(CLI::App& app) {
    app.formatter(std::make_shared<Formatter>());
    // Parsed without complaint; check_parsed refuses a second one with vplkit's own line.
    app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast)->group("options");
    app.set_help_flag("-h,--help", "this help");
}

CLI::App* add_command(CLI::App& parent, const std::string& name, const std::string& summary, const std::string& about) {
    CLI::App* command = parent.add_subcommand(name, about.empty() ? summary : summary + "\n\n" + about);
    command->group("commands");
    if (CLI::Option* help = command->get_help_ptr()) help->group("options");
    command->allow_extras();  // reported by check_parsed, as vplkit words it
    return command;
}

std::string command_path(const CLI::App& command) {
    std::string path;
    for (const CLI::App* at = &command; at && at->get_parent(); at = at->get_parent()) {
        path = at->get_name() + (path.empty() ? "" : " " + path);
    }
    return path.empty() ? command.get_name() : path;
}

void check_parsed(const CLI::App& command) {
    const std::string path = command_path(command);
    for (const CLI::Option* option : command.get_options()) {
        if (option->count() > 1 && option->get_multi_option_policy() != CLI::MultiOptionPolicy::TakeAll) {
            throw UsageError("option '" + option->get_name() + "' given more than once for '" + path + "'");
        }
    }
    const std::vector<std::string> left = command.remaining();
    if (left.empty()) return;
    const std::string& first = left.front();
    if (first.size() > 1 && first[0] == '-') {
        throw UsageError("unknown option '" + first.substr(0, first.find('=')) + "' for '" + path + "'");
    }
    throw UsageError("unexpected argument '" + first + "' for '" + path + "'");
}

std::string parse_error_text(const CLI::ParseError& error) {
    std::string text = error.what();
    // CLI11's own wording for a missing or unreadable value, said as vplkit says it.
    std::smatch match;
    if (std::regex_match(text, match, std::regex(R"((\S+): \d+ required \S+ missing)"))) {
        return match[1].str() + " needs a value";
    }
    if (std::regex_match(text, match, std::regex(R"(Could not convert: (\S+) = (.*))"))) {
        return match[1].str() + " does not take '" + match[2].str() + "' (a switch: give it alone, or =true/=false)";
    }
    // A check's "expects ..." reads after the option's name: "--spp expects a whole number ...".
    const size_t colon = text.find(": expects ");
    if (colon != std::string::npos && text.rfind(' ', colon) == std::string::npos) text.erase(colon, 1);
    return text;
}

}  // namespace vplkit::cli

// --help in clppm's layout for the CLI11 apps (the render options, `clppm compare`): the usage
// lines, then the description, then "-o, --output FILE" in a fixed first column and the option's
// description, which the caller wraps with wrapped() (CLI11 indents its continuation lines).
#pragma once
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>

namespace clppm {

// Word-wraps `text` to `width` columns, '\n' between lines.
inline std::string wrapped(const std::string& text, size_t width) {
    std::istringstream words(text);
    std::string out, word;
    size_t column = 0;
    while (words >> word) {
        if (column > 0 && column + 1 + word.size() > width) {
            out += '\n';
            column = 0;
        } else if (column > 0) {
            out += ' ';
            ++column;
        }
        out += word;
        column += word.size();
    }
    return out;
}

class HelpFormatter : public CLI::Formatter {
public:
    HelpFormatter(std::string usage, size_t first_column) : usage_(std::move(usage)) { column_width(first_column); }
    std::string make_option_name(const CLI::Option* opt, bool positional) const override {
        if (positional) return opt->get_name(true, false);
        std::string names;
        for (const std::string& s : opt->get_snames()) names += "-" + s + ", ";
        if (opt->get_snames().empty()) names += "    ";
        for (const std::string& l : opt->get_lnames()) names += "--" + l;
        return names;
    }
    std::string make_option_opts(const CLI::Option* opt) const override {
        return opt->get_type_size() == 0 || opt->get_type_name().empty() ? std::string() : " " + opt->get_type_name();
    }
    // The usage lines first, then what the command does (CLI11 puts the description first).
    std::string make_description(const CLI::App*) const override { return std::string(); }
    std::string make_usage(const CLI::App* app, std::string) const override {
        return usage_ + app->get_description() + "\n";
    }

private:
    std::string usage_;
};

} // namespace clppm

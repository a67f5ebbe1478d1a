#include "scene/gltf/gltf_context.h"

#include <sstream>

namespace clppm::gltf {

std::string one_line(const std::string& text) {
    std::string out;
    bool pending_break = false;
    for (char c : text) {
        if (c == '\n' || c == '\r') {
            pending_break = !out.empty();
            continue;
        }
        if (pending_break) out += "; ";
        pending_break = false;
        out += (c == '\t') ? ' ' : c;
    }
    return out;
}

std::string clipped(const std::string& text, size_t max_chars) {
    return text.size() <= max_chars ? text : text.substr(0, max_chars) + "...";
}

std::vector<std::string> split_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (!line.empty() && line != "\r") lines.push_back(one_line(line));
    return lines;
}

} // namespace clppm::gltf

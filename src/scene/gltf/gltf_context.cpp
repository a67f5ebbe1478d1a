#include "scene/gltf/gltf_context.h"

#include <cctype>
#include <sstream>

namespace clppm::gltf {

const tinygltf::Value* scene_extra(const tinygltf::Model& model, const char* key) {
    if (model.scenes.empty()) return nullptr;
    const size_t index = model.defaultScene >= 0 ? size_t(model.defaultScene) : 0;
    if (index >= model.scenes.size()) return nullptr; // the scene builder has said so
    const tinygltf::Value& extras = model.scenes[index].extras;
    if (!extras.IsObject() || !extras.Has(key)) return nullptr;
    return &extras.Get(key);
}

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

std::string printable(const std::string& text) {
    std::string out;
    for (char c : text) {
        const unsigned char u = static_cast<unsigned char>(c);
        if (c == '\n') out += "\\n";
        else if (c == '\r') out += "\\r";
        else if (c == '\t') out += "\\t";
        else if (u < 0x20 || u == 0x7f) {
            static const char kHex[] = "0123456789abcdef";
            out += "\\x";
            out += kHex[u >> 4];
            out += kHex[u & 15];
        } else out += c;
    }
    return out;
}

std::string clipped(const std::string& text, size_t max_chars) {
    // A data URI's payload is never worth reading in a message: its length says enough.
    std::string out;
    for (size_t i = 0; i < text.size();) {
        const size_t at = text.find("data:", i);
        const size_t comma = at == std::string::npos ? at : text.find(',', at);
        if (comma == std::string::npos) {
            out += text.substr(i);
            break;
        }
        size_t end = comma + 1;
        while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '+' ||
                                     text[end] == '/' || text[end] == '='))
            ++end;
        out += text.substr(i, comma + 1 - i) + "<" + std::to_string(end - comma - 1) + " characters>";
        i = end;
    }
    return out.size() <= max_chars ? out : out.substr(0, max_chars) + "...";
}

std::vector<std::string> split_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (!line.empty() && line != "\r") lines.push_back(one_line(line));
    return lines;
}

} // namespace clppm::gltf

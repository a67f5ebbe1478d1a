// An enum's names spelled once: beside each enum a table of EnumName and an enum_names(E) that
// returns it (found by argument-dependent lookup), and from it to_string, enum_from_name and the
// "a, b or c" list of choices that options, --help, --stats-json and the Python module print.
#pragma once
#include <iterator>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "util/text.h"

namespace clppm {

template <class E>
struct EnumName {
    E value;
    const char* name;
};

// The name of e ("?" for a value outside the table).
template <class E, class = decltype(enum_names(E{}))>
const char* to_string(E e) {
    for (const auto& n : enum_names(e))
        if (n.value == e) return n.name;
    return "?";
}

// The value whose name is `name`, ignoring ASCII case, or nullopt.
template <class E>
std::optional<E> enum_from_name(std::string_view name) {
    const std::string folded = lower(std::string(name));
    for (const auto& n : enum_names(E{}))
        if (folded == n.name) return n.value;
    return std::nullopt;
}

// The names in order, as "a, b or c".
template <class E>
std::string enum_choices() {
    std::vector<std::string> names;
    for (const auto& n : enum_names(E{})) names.push_back(n.name);
    return either(names);
}

} // namespace clppm

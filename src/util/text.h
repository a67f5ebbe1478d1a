// Small text helpers every layer uses: ASCII case folding, a case-blind suffix test, and the
// "a, b or c" lists of messages and --help.
#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace clppm {

// s in ASCII lower case.
std::string lower(std::string s);

// Whether s ends with suffix, ignoring ASCII case.
bool ends_with_ci(std::string_view s, std::string_view suffix);

// "a", "a or b", "a, b or c".
std::string either(const std::vector<std::string>& names);

} // namespace clppm

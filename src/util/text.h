// Small text helpers every layer uses: ASCII case folding, a case-blind suffix test, the
// "a, b or c" lists of messages and --help, and numbers in messages.
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

// x as printf's %g writes it: the shortest of a message's numbers.
std::string number_text(double x);

} // namespace clppm

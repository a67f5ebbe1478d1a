// Reading one option's value as typed: integers, reals, colours and choices, each refused with one
// line that names the option as the user spelled it and the values it takes
// ("--alpha 1.5: must be in (0, 1]").
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "util/enum_names.h"
#include "util/text.h"

namespace clppm {

// One occurrence of an option: its name as typed ("-o", "--output"), the value, and the range
// every message about it ends with (nullptr when any value goes).
struct OptionArg {
    const std::string& shown;
    const std::string& value;
    const char* range;
};

[[noreturn]] void bad_value(const OptionArg& a);

int64_t parse_int(const OptionArg& a, int64_t lo, int64_t hi);
// Unsigned 64-bit; a sign is refused (strtoull would wrap "-1").
uint64_t parse_u64(const OptionArg& a);
// A finite real accepted by `ok` ("nan" and "inf" never are).
double parse_real(const OptionArg& a, bool (*ok)(double));
// "R,G,B": three finite numbers >= 0.
std::array<float, 3> parse_rgb(const OptionArg& a);
// One number for all three channels, or R,G,B, each finite and >= 0.
std::array<float, 3> parse_rgb_or_number(const OptionArg& a);
// The value, refused when empty.
const std::string& non_empty(const OptionArg& a);

// One of an enum's names (util/enum_names.h), in any case ("--filter Tent").
template <class E>
E parse_enum(const OptionArg& a) {
    if (const std::optional<E> v = enum_from_name<E>(a.value)) return *v;
    bad_value(a);
}
// The enum's names as an option's range, "a, b or c", kept for the option table's lifetime.
template <class E>
const char* enum_range() {
    static const std::string range = enum_choices<E>();
    return range.c_str();
}

} // namespace clppm

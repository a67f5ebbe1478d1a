#include "render/option_values.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "util/error.h"

namespace clppm {

void bad_value(const OptionArg& a) {
    const std::string shown_value = a.value.empty() ? "''" : a.value;
    throw Error(a.shown + " " + shown_value + ": must be " + (a.range ? a.range : "something else"));
}

int64_t parse_int(const OptionArg& a, int64_t lo, int64_t hi) {
    const std::string& v = a.value;
    if (v.empty() || !(std::isdigit(static_cast<unsigned char>(v[0])) || v[0] == '-' || v[0] == '+')) bad_value(a);
    errno = 0;
    char* end = nullptr;
    const long long n = std::strtoll(v.c_str(), &end, 10);
    if (errno == ERANGE || *end != '\0' || n < lo || n > hi) bad_value(a);
    return n;
}

uint64_t parse_u64(const OptionArg& a) {
    const std::string& v = a.value;
    if (v.empty() || !std::isdigit(static_cast<unsigned char>(v[0]))) bad_value(a);
    errno = 0;
    char* end = nullptr;
    const unsigned long long n = std::strtoull(v.c_str(), &end, 10);
    if (errno == ERANGE || *end != '\0') bad_value(a);
    return n;
}

double parse_real(const OptionArg& a, bool (*ok)(double)) {
    const std::string& v = a.value;
    if (v.empty() || std::isspace(static_cast<unsigned char>(v[0]))) bad_value(a);
    errno = 0;
    char* end = nullptr;
    const double x = std::strtod(v.c_str(), &end);
    if (errno == ERANGE || *end != '\0' || !std::isfinite(x) || !ok(x)) bad_value(a);
    return x;
}

std::array<float, 3> parse_rgb(const OptionArg& a) {
    std::array<float, 3> c{};
    const std::string& v = a.value;
    size_t start = 0;
    for (int k = 0; k < 3; ++k) {
        const size_t comma = v.find(',', start);
        if ((k < 2) != (comma != std::string::npos)) bad_value(a);
        const std::string part = v.substr(start, k < 2 ? comma - start : std::string::npos);
        if (part.empty() || std::isspace(static_cast<unsigned char>(part[0]))) bad_value(a);
        errno = 0;
        char* end = nullptr;
        const double x = std::strtod(part.c_str(), &end);
        if (errno == ERANGE || *end != '\0' || !std::isfinite(x) || x < 0 || !std::isfinite(float(x))) bad_value(a);
        c[size_t(k)] = float(x);
        start = comma + 1;
    }
    return c;
}

std::array<float, 3> parse_rgb_or_number(const OptionArg& a) {
    if (a.value.find(',') != std::string::npos) return parse_rgb(a);
    const float x = float(parse_real(a, [](double v) { return v >= 0 && std::isfinite(float(v)); }));
    return {x, x, x};
}

const std::string& non_empty(const OptionArg& a) {
    if (a.value.empty()) bad_value(a);
    return a.value;
}

} // namespace clppm

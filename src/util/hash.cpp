#include "util/hash.h"

namespace clppm {

unsigned long long fnv1a64(const std::string& data, unsigned long long h) {
    for (unsigned char c : data) {
        h ^= c;
        h *= 1099511628211ull;
    }
    return h;
}

} // namespace clppm

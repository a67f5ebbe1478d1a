// 64-bit FNV-1a: program cache keys, checkpoint checksums and scene fingerprints.
#pragma once
#include <string>
#include <vector>

namespace clppm {

constexpr unsigned long long kFnv1a64Basis = 1469598103934665603ull;

unsigned long long fnv1a64(const std::string& data, unsigned long long h = kFnv1a64Basis);

// The bytes of a vector of plain values, hashed on from h.
template <class T>
unsigned long long fnv1a64(const std::vector<T>& v, unsigned long long h) {
    return fnv1a64(std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T)), h);
}

} // namespace clppm

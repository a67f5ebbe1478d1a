// The complete progressive state of a render, saved atomically so that a render stopped at any
// point resumes to the same image, bit for bit on the same device with the same seed.
//
// File layout: "CLPPMCK1", a little-endian u64 header length, the header (JSON: the fingerprint of
// the scene and the options that shape the image, the pass counters), then named blobs (u32 name
// length, name, u64 size, bytes), and a trailing u64 FNV-1a checksum of everything before it.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "io/stats_json.h"

namespace clppm {

struct Checkpoint {
    Json header = Json::object();
    std::map<std::string, std::vector<unsigned char>> blobs;

    template <class T>
    void put(const std::string& name, const std::vector<T>& v) {
        const unsigned char* p = reinterpret_cast<const unsigned char*>(v.data());
        blobs[name].assign(p, p + v.size() * sizeof(T));
    }
    // The blob `name` as n elements of T; throws Error when missing or of another size.
    template <class T>
    std::vector<T> get(const std::string& name, size_t n) const {
        std::vector<T> v(n);
        const std::vector<unsigned char>& b = blob(name, n * sizeof(T));
        if (n) std::copy(b.begin(), b.end(), reinterpret_cast<unsigned char*>(v.data()));
        return v;
    }
    const std::vector<unsigned char>& blob(const std::string& name, size_t expected_bytes) const;
    std::string path; // where it was read from, for messages
};

// Writes atomically (temp file, fsync, rename); throws Error naming the path.
void write_checkpoint(const std::string& path, const Checkpoint& ck);

// Reads and verifies magic and checksum; throws Error naming the path on any damage.
Checkpoint read_checkpoint(const std::string& path);

// The options of the header that must match for a resume; returns "" when `saved` and `now`
// agree, else one line naming each difference ("--alpha 0.7 in the checkpoint, 0.5 now; ...").
std::string checkpoint_differences(const Json& saved, const Json& now);

} // namespace clppm

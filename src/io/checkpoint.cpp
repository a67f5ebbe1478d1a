#include "io/checkpoint.h"

#include <cstring>
#include <fstream>
#include <sstream>

#include "io/atomic_file.h"
#include "io/regular_file.h"
#include "util/error.h"
#include "util/hash.h"

namespace clppm {

namespace {

constexpr char kMagic[8] = {'C', 'L', 'P', 'P', 'M', 'C', 'K', '1'};

void put_u64(std::string& out, uint64_t v) {
    for (int i = 0; i < 8; ++i) out.push_back(char((v >> (8 * i)) & 0xff));
}

struct Reader {
    const std::string& data;
    size_t pos = 0;
    const std::string& path;
    void need(size_t n) const {
        if (data.size() - pos < n) throw Error(path + ": checkpoint is truncated");
    }
    uint64_t u64() {
        need(8);
        uint64_t v = 0;
        for (int i = 0; i < 8; ++i) v |= uint64_t(uint8_t(data[pos + i])) << (8 * i);
        pos += 8;
        return v;
    }
    std::string bytes(size_t n) {
        need(n);
        std::string s = data.substr(pos, n);
        pos += n;
        return s;
    }
};

} // namespace

const std::vector<unsigned char>& Checkpoint::blob(const std::string& name, size_t expected_bytes) const {
    auto it = blobs.find(name);
    if (it == blobs.end()) throw Error(path + ": checkpoint has no '" + name + "' data");
    if (it->second.size() != expected_bytes)
        throw Error(path + ": checkpoint '" + name + "' holds " + std::to_string(it->second.size()) +
                    " bytes, expected " + std::to_string(expected_bytes));
    return it->second;
}

void write_checkpoint(const std::string& path, const Checkpoint& ck) {
    std::string out(kMagic, sizeof kMagic);
    const std::string header = ck.header.dump();
    put_u64(out, header.size());
    out += header;
    for (const auto& [name, data] : ck.blobs) {
        const uint32_t len = uint32_t(name.size());
        for (int i = 0; i < 4; ++i) out.push_back(char((len >> (8 * i)) & 0xff));
        out += name;
        put_u64(out, data.size());
        out.append(reinterpret_cast<const char*>(data.data()), data.size());
    }
    put_u64(out, fnv1a64(out));
    write_file_atomic(path, out);
}

Checkpoint read_checkpoint(const std::string& path) {
    if (const std::string why = not_a_regular_file(path); !why.empty())
        throw Error(path + ": cannot read checkpoint (" + why + ")");
    std::ifstream f(path, std::ios::binary);
    if (!f) throw Error(path + ": cannot read checkpoint (" + std::strerror(errno) + ")");
    std::ostringstream ss;
    ss << f.rdbuf();
    const std::string data = ss.str();
    if (data.size() < sizeof kMagic + 16 || std::memcmp(data.data(), kMagic, sizeof kMagic) != 0)
        throw Error(path + ": not a clppm checkpoint");
    Reader tail{data, data.size() - 8, path};
    if (tail.u64() != fnv1a64(data.substr(0, data.size() - 8)))
        throw Error(path + ": checkpoint is damaged (checksum mismatch)");
    const std::string body = data.substr(0, data.size() - 8);
    Reader r{body, sizeof kMagic, path};
    Checkpoint ck;
    ck.path = path;
    const uint64_t header_len = r.u64();
    try {
        ck.header = Json::parse(r.bytes(header_len));
    } catch (const nlohmann::json::exception&) {
        throw Error(path + ": checkpoint header is not valid JSON");
    }
    while (r.pos < body.size()) {
        r.need(4);
        uint32_t len = 0;
        for (int i = 0; i < 4; ++i) len |= uint32_t(uint8_t(body[r.pos + i])) << (8 * i);
        r.pos += 4;
        std::string name = r.bytes(len);
        const uint64_t size = r.u64();
        std::string bytes = r.bytes(size);
        ck.blobs[name].assign(bytes.begin(), bytes.end());
    }
    return ck;
}

std::string checkpoint_differences(const Json& saved, const Json& now) {
    std::string diff;
    for (auto it = now.begin(); it != now.end(); ++it) {
        const std::string& key = it.key();
        const Json* old = saved.contains(key) ? &saved[key] : nullptr;
        if (old && *old == it.value()) continue;
        if (!diff.empty()) diff += "; ";
        diff += key + " " + (old ? old->dump() : std::string("(absent)")) + " in the checkpoint, " + it.value().dump() +
                " now";
    }
    return diff;
}

} // namespace clppm

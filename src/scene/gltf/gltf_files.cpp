#include "scene/gltf/gltf_files.h"

#include <filesystem>
#include <fstream>

#include "io/regular_file.h"
#include "scene/gltf/gltf_context.h"

namespace clppm::gltf {

namespace fs = std::filesystem;

std::vector<unsigned char> read_whole_file(const std::string& path, std::string* why) {
    std::error_code ec;
    *why = not_a_regular_file(path);
    uint64_t size = why->empty() ? fs::file_size(path, ec) : 0;
    if (why->empty() && ec) *why = ec.message();
    if (why->empty() && size > kMaxFileBytes) *why = "larger than 1 GiB";
    if (!why->empty()) return {};
    std::ifstream in(path, std::ios::binary);
    std::vector<unsigned char> bytes(static_cast<size_t>(size));
    if (!in || (size && !in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)))) {
        *why = "read error";
        return {};
    }
    return bytes;
}

bool path_inside(const std::string& path, const std::string& base) {
    if (base.empty()) return false;
    fs::path rel = fs::path(path).lexically_normal().lexically_relative(base);
    return !rel.empty() && rel != "." && *rel.begin() != "..";
}

bool resolves_inside(const std::string& path, const std::string& base) {
    std::error_code ec, base_ec;
    fs::path real = fs::weakly_canonical(path, ec), real_base = fs::weakly_canonical(base, base_ec);
    return !ec && !base_ec && path_inside(real.string(), real_base.string());
}

std::string absolute_dir(const std::string& dir) {
    std::error_code ec;
    fs::path p = dir.empty() ? fs::current_path(ec) : fs::absolute(dir, ec);
    p = p.lexically_normal();
    if (!p.has_filename() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
    return p.string();
}

bool guarded_file_exists(const std::string& path, void* user) {
    const auto* guard = static_cast<const FsGuard*>(user);
    std::error_code ec;
    return path_inside(path, guard->base) && fs::is_regular_file(path, ec);
}

std::string unexpanded_path(const std::string& path, void*) { return path; }

bool guarded_read_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    auto* guard = static_cast<FsGuard*>(user);
    std::string why = "outside the scene directory";
    if (path_inside(path, guard->base) && !resolves_inside(path, guard->base))
        why = "a symbolic link that leads outside the scene directory";
    else if (path_inside(path, guard->base)) *out = read_whole_file(path, &why);
    guard->bytes_read += out->size();
    if (why.empty() && guard->bytes_read > kMaxExternalBytes) why = "external files exceed 2 GiB in total";
    if (why.empty()) return true;
    out->clear();
    if (err) *err += path + ": " + why + "\n";
    return false;
}

bool refuse_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "clppm never writes glTF files\n";
    return false;
}

} // namespace clppm::gltf

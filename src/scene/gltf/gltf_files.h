// File access for the loader: whole files with a size limit, and tinygltf's file-system
// callbacks, which keep every external file inside the scene's directory (symbolic links
// included) and within a total budget.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace clppm::gltf {

// The bytes of a file; on failure an empty vector and the reason in *why (empty on success).
std::vector<unsigned char> read_whole_file(const std::string& path, std::string* why);
// True when `path` lies inside directory `base` (both compared lexically, after normalisation).
bool path_inside(const std::string& path, const std::string& base);
// The same after resolving symbolic links: a link inside the directory may not lead out of it.
bool resolves_inside(const std::string& path, const std::string& base);
std::string absolute_dir(const std::string& dir);

// tinygltf file-system callbacks: every external file must lie inside the scene's directory
// (this also stops tinygltf's fallback search of the working directory). `user` is a FsGuard.
struct FsGuard {
    std::string base;        // absolute; empty: no external files at all
    uint64_t bytes_read = 0; // many buffers may name the same big file
};
bool guarded_file_exists(const std::string& path, void* user);
std::string unexpanded_path(const std::string& path, void*);
bool guarded_read_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user);
bool refuse_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*);

} // namespace clppm::gltf

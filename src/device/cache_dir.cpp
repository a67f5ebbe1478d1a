#include "device/cache_dir.h"

#include <cstdlib>
#include <sys/stat.h>

namespace clppm {

std::string cache_dir() {
    if (const char* e = std::getenv("CLPPM_NO_CACHE"); e && *e && std::string(e) != "0") return "";
    if (const char* e = std::getenv("CLPPM_CACHE_DIR"); e && *e) return e;
    if (const char* e = std::getenv("XDG_CACHE_HOME"); e && *e) return std::string(e) + "/clppm";
    if (const char* e = std::getenv("HOME"); e && *e) return std::string(e) + "/.cache/clppm";
    return "";
}

void make_dirs(const std::string& path) {
    for (size_t i = 1; i <= path.size(); ++i)
        if (i == path.size() || path[i] == '/') ::mkdir(path.substr(0, i).c_str(), 0755);
}

} // namespace clppm

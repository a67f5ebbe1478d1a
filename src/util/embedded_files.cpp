#include "util/embedded_files.h"

namespace clppm {

const EmbeddedFile* find_embedded(const std::string& path) {
    size_t count = 0;
    const EmbeddedFile* files = embedded_files(&count);
    for (size_t i = 0; i < count; ++i)
        if (path == files[i].path) return &files[i];
    return nullptr;
}

} // namespace clppm

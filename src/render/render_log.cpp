#include "render/render_log.h"

#include <cstdio>

#include "device/cluster.h"

namespace clppm {

RenderLog::RenderLog(bool quiet) : quiet_(quiet), speaks_(cluster().rank() == 0) {}

RenderLog RenderLog::silent() {
    RenderLog log(true);
    log.speaks_ = false;
    return log;
}

void RenderLog::note(const std::string& message) const {
    if (!quiet_ && speaks_) std::fprintf(stderr, "clppm: %s\n", message.c_str());
}

void RenderLog::warn(const std::string& message) {
    warnings_.push_back(message);
    if (speaks_) std::fprintf(stderr, "clppm: warning: %s\n", message.c_str());
}

void RenderLog::error(const std::string& message) {
    warnings_.push_back(message);
    if (speaks_) std::fprintf(stderr, "clppm: error: %s\n", message.c_str());
}

} // namespace clppm

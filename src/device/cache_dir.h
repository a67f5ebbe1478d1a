// clppm's cache folder: built programs (device/kernel_program.h) and measured device choices
// (render/device_auto.h) live there.
#pragma once
#include <string>

namespace clppm {

// $CLPPM_CACHE_DIR, else $XDG_CACHE_HOME/clppm, else ~/.cache/clppm; empty when CLPPM_NO_CACHE=1
// turns the cache off (or no home is known).
std::string cache_dir();

// Creates `path` and the folders above it as needed (mkdir -p); what exists is left alone.
void make_dirs(const std::string& path);

} // namespace clppm

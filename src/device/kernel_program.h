// Assembling kernel sources (embedded, or from a directory during development), building them for
// a device with a persistent binary cache, and reporting build failures with the build log.
#pragma once
#include <string>
#include <vector>

#include "device/cl.h"
#include "device/device.h"

namespace clppm {

// Where kernel sources come from: the embedded copies, unless CLPPM_KERNEL_DIR or, on this thread,
// a KernelDirScope (--kernel-dir, for one render) names a directory to read kernels/*.cl from.
std::string kernel_dir();
class KernelDirScope {
public:
    explicit KernelDirScope(const std::string& dir); // empty: no change; `dir` outlives the scope
    ~KernelDirScope();
    KernelDirScope(const KernelDirScope&) = delete;
    KernelDirScope& operator=(const KernelDirScope&) = delete;

private:
    const std::string* previous_;
};

// The full source of a kernel file with every `#include "x"` resolved from the same source
// (each file included once), so the driver never needs an include path.
std::string assemble_kernel_source(const std::string& name);

struct ProgramBuildStats {
    double seconds = 0;
    bool from_cache = false;   // loaded from clppm's cache
    bool driver_cache = false; // the driver keeps its own (PoCL), so clppm's is not used
    std::string options;       // as passed to the compiler
};

// Builds (or loads from the cache) the program for `entry_file` with `options`. Throws Error with
// the device's build log on failure. The cache lives in $CLPPM_CACHE_DIR, else
// $XDG_CACHE_HOME/clppm, else ~/.cache/clppm; CLPPM_NO_CACHE=1 disables it. Drivers that keep
// their own cache (PoCL) get none from clppm.
cl::Program build_program(const DeviceContext& dc, const std::string& entry_file, const std::string& options,
                          ProgramBuildStats* stats = nullptr);

} // namespace clppm

#include "render/job_fingerprint.h"

#include <cstdio>

#include "render/option_table.h"
#include "util/error.h"
#include "util/hash.h"

namespace clppm {

namespace {

std::string hex(uint64_t v) {
    char s[17];
    std::snprintf(s, sizeof s, "%016llx", static_cast<unsigned long long>(v));
    return s;
}

} // namespace

Json job_fingerprint(const RenderOptions& o, const DeviceScene& ds, uint64_t scene_hash,
                     const std::string& kernel_source) {
    Json fp = option_values(o, OptionRole::Image);
    fp["--width"] = ds.camera.width; // as the camera resolved them
    fp["--height"] = ds.camera.height;
    fp["scene"] = hex(scene_hash);
    fp["kernels"] = hex(fnv1a64(kernel_source));
    return fp;
}

Checkpoint open_resume(const std::string& path, const Json& fingerprint) {
    Checkpoint ck = read_checkpoint(path);
    if (!ck.header.contains("fingerprint")) throw Error(path + ": checkpoint has no fingerprint");
    const std::string diff = checkpoint_differences(ck.header["fingerprint"], fingerprint);
    if (!diff.empty()) throw Error("--resume " + path + ": cannot continue this render: " + diff);
    return ck;
}

} // namespace clppm

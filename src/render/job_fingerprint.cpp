#include "render/job_fingerprint.h"

#include <cstdio>

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
    const RenderSettings& s = o.settings;
    Json j;
    j["scene"] = hex(scene_hash);
    j["kernels"] = hex(fnv1a64(kernel_source));
    j["--integrator"] = s.integrator;
    j["--direct"] = to_string(s.direct);
    j["--width"] = ds.camera.width;
    j["--height"] = ds.camera.height;
    j["--camera"] = s.camera;
    j["--spp"] = s.spp;
    j["--photons"] = s.photons;
    j["--alpha"] = s.alpha;
    j["--radius"] = s.radius;
    j["--seed"] = s.seed;
    j["--max-bounces"] = s.max_bounces;
    j["--filter"] = to_string(s.filter);
    j["--aperture"] = s.aperture;
    j["--focus-distance"] = s.focus_distance;
    return j;
}

Checkpoint open_resume(const std::string& path, const Json& fingerprint) {
    Checkpoint ck = read_checkpoint(path);
    if (!ck.header.contains("fingerprint")) throw Error(path + ": checkpoint has no fingerprint");
    const std::string diff = checkpoint_differences(ck.header["fingerprint"], fingerprint);
    if (!diff.empty()) throw Error("--resume " + path + ": cannot continue this render: " + diff);
    return ck;
}

} // namespace clppm

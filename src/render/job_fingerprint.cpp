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
    return {{"scene", hex(scene_hash)},
            {"kernels", hex(fnv1a64(kernel_source))},
            {"--integrator", s.integrator},
            {"--direct", to_string(s.direct)},
            {"--width", ds.camera.width},
            {"--height", ds.camera.height},
            {"--camera", s.camera},
            {"--spp", s.spp},
            {"--photons", s.photons},
            {"--alpha", s.alpha},
            {"--radius", s.radius},
            {"--seed", s.seed},
            {"--max-bounces", s.max_bounces},
            {"--filter", to_string(s.filter)},
            {"--aperture", s.aperture},
            {"--focus-distance", s.focus_distance},
            {"--sampler", to_string(s.sampler)},
            {"--visual-importance", s.visual_importance},
            {"--disc-coverage", to_string(s.disc_coverage)}};
}

Checkpoint open_resume(const std::string& path, const Json& fingerprint) {
    Checkpoint ck = read_checkpoint(path);
    if (!ck.header.contains("fingerprint")) throw Error(path + ": checkpoint has no fingerprint");
    const std::string diff = checkpoint_differences(ck.header["fingerprint"], fingerprint);
    if (!diff.empty()) throw Error("--resume " + path + ": cannot continue this render: " + diff);
    return ck;
}

} // namespace clppm

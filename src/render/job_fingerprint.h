// What a checkpoint must agree on to be resumed: the scene, the kernels and every option that
// shapes the image (io/checkpoint.h compares them and names what differs).
#pragma once
#include <cstdint>
#include <string>

#include "io/checkpoint.h"
#include "render/render_options.h"
#include "scene/device_scene.h"

namespace clppm {

// `kernel_source`: the assembled source and its build options.
Json job_fingerprint(const RenderOptions& options, const DeviceScene& scene, uint64_t scene_hash,
                     const std::string& kernel_source);

// Reads the checkpoint at `path` and refuses it when its fingerprint differs from `fingerprint`.
Checkpoint open_resume(const std::string& path, const Json& fingerprint);

} // namespace clppm

// Helpers shared by the tests: the PoCL device, temporary directories, running the clppm binary.
#pragma once
#include <string>

#include "device/device.h"

namespace clppm::test {

// The device tests run on: $CLPPM_TEST_DEVICE if set (a --device spec), else the first CPU
// device, else device 0.
const DeviceInfo& test_device();

// A fresh empty directory under the build's temporary space.
std::string make_temp_dir(const std::string& tag);

// Runs a shell command; returns its exit status and captures stdout+stderr into *output.
int run_command(const std::string& cmd, std::string* output);

// Path of the clppm executable under test.
std::string clppm_binary();

// Runs the clppm executable with `args` (a shell-quoted string); like run_command.
int run_clppm(const std::string& args, std::string* output);

} // namespace clppm::test

#include "io/image_io.h"
#include "integrators/integrator.h"
#include "integrators/render_settings.h"
#include "scene/scene.h"

namespace clppm::test {

// Renders `scene` in this process on test_device() for `passes` passes and returns the image.
Image render_passes(Scene scene, const RenderSettings& settings, uint64_t passes, IntegratorStats* stats = nullptr);

// Mean of channel c (or of all channels when c < 0) over the pixel rectangle [x0,x1) x [y0,y1).
double region_mean(const Image& img, int x0, int y0, int x1, int y1, int c = -1);

} // namespace clppm::test

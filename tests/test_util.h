// Helpers shared by the tests: the PoCL device, temporary directories, running the clppm binary.
#pragma once
#include <string>

#include "device.h"

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

} // namespace clppm::test

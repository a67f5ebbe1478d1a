// Helpers shared by the tests: the PoCL device, temporary directories, running the clppm binary.
#pragma once
#include <array>
#include <string>

#include "device/device.h"

namespace clppm::test {

// The device tests run on: $CLPPM_TEST_DEVICE if set (a --device spec), else the first CPU
// device, else device 0.
const DeviceInfo& test_device();

// A made-up device for tests of device choice and memory: no OpenCL object behind it.
DeviceInfo fake_device(int index, const std::string& platform, const std::string& name, cl_device_type type,
                       size_t global_mem = 0, size_t max_alloc = 0);

// A fresh empty directory under the build's temporary space.
std::string make_temp_dir(const std::string& tag);

// Runs a shell command; returns its exit status and captures stdout+stderr into *output.
int run_command(const std::string& cmd, std::string* output);

// The whole contents of a file ("" when it cannot be read).
std::string slurp(const std::string& path);

// Path of the clppm executable under test.
std::string clppm_binary();

// Runs the clppm executable with `args` (a shell-quoted string); like run_command.
int run_clppm(const std::string& args, std::string* output);

// Renders `args` for 5 passes straight, and for 2 passes with a checkpoint resumed to 5: the two
// images are equal bit for bit (and differ from the 2-pass one, so the test can fail). Returns
// the temporary folder holding full.exr, part.exr, res.exr and c.ck.
std::string expect_resume_is_exact(const std::string& args, const std::string& what);

// The mean radiance of tests/data/<file> rendered by the clppm executable at 48x32 with
// `integrator` for `passes` passes of `photons` photons (the same seed every time); a failed
// run is a test failure. The material and geometry tests compare such means of scene pairs.
double render_test_scene_mean(const std::string& file, const std::string& integrator, int passes = 6,
                              int photons = 50000);

// The same per channel, at width x height.
std::array<double, 3> render_test_scene_channels(const std::string& file, const std::string& integrator, int passes,
                                                 int photons = 50000, int width = 16, int height = 16);

// For SPPM and the path tracer: the means of tests/data/<file> and <reference> (rendered as
// render_test_scene_mean does) agree within `tolerance`, relative.
void expect_scenes_render_alike(const std::string& file, const std::string& reference, double tolerance, int passes = 6,
                                int photons = 50000);

} // namespace clppm::test

#include <algorithm>
#include <cmath>
#include <vector>

#include "device/cl.h"
#include "integrators/integrator.h"
#include "integrators/render_settings.h"
#include "io/image_io.h"
#include "scene/scene.h"

namespace clppm::test {

// Renders `scene` in this process on test_device() for `passes` passes and returns the image.
Image render_passes(Scene scene, const RenderSettings& settings, uint64_t passes, IntegratorStats* stats = nullptr);

// The factor by which a test's hang guard (a bound no healthy run comes near) is stretched:
// $CLPPM_TEST_TIME_SCALE, default 1; scripts/test_sanitized.sh sets it for its slower build.
double time_scale();

// A double-precision 3-vector for the host references.
struct D3 {
    double x, y, z;
};
inline D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline D3 operator*(double s, D3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline D3 operator*(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double length(D3 a) { return std::sqrt(dot(a, a)); }
inline D3 normalized(D3 a) { return (1.0 / length(a)) * a; }
inline D3 d3(const float* v) { return {v[0], v[1], v[2]}; }
inline D3 d3(const Vec3& v) { return {v.x, v.y, v.z}; }
// A frame (t, b) about unit n by Gram-Schmidt against the least aligned axis, independent of the
// kernels' make_frame.
inline void host_frame(D3 n, D3& t, D3& b) {
    D3 h = std::fabs(n.x) < 0.5 ? D3{1, 0, 0} : D3{0, 1, 0};
    t = normalized(h - dot(h, n) * n);
    b = cross(n, t);
}

// A program built from `source` for dc's device as OpenCL C 1.2; a build failure is a test
// failure with the build log.
cl::Program build_test_program(const DeviceContext& dc, const std::string& source);

// A test's own kernel program on test_device(): kernel files' sources (assemble_kernel_source)
// followed by the test's wrapper kernels, built as OpenCL C 1.2; a build failure is a test failure
// with the build log. Buffers in and out, and 1-D launches.
// n values of T from a device buffer (a blocking read on dc's queue).
template <class T>
std::vector<T> read_buffer(const DeviceContext& dc, const cl::Buffer& b, size_t n) {
    std::vector<T> v(n);
    dc.queue.enqueueReadBuffer(b, CL_TRUE, 0, n * sizeof(T), v.data());
    return v;
}

struct KernelHarness {
    DeviceContext dc{test_device()};
    cl::Program program;

    explicit KernelHarness(const std::string& source);
    template <class T>
    cl::Buffer input(const std::vector<T>& v) const {
        return cl::Buffer(dc.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                          std::max<size_t>(1, v.size()) * sizeof(T), const_cast<T*>(v.data()));
    }
    cl::Buffer output(size_t bytes) const { return cl::Buffer(dc.context, CL_MEM_WRITE_ONLY, bytes); }
    template <class T>
    std::vector<T> read(const cl::Buffer& b, size_t n) const {
        return read_buffer<T>(dc, b, n);
    }
    void run(cl::Kernel& k, size_t n) const { dc.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(n)); }
};

// Mean of channel c (or of all channels when c < 0) over the pixel rectangle [x0,x1) x [y0,y1).
double region_mean(const Image& img, int x0, int y0, int x1, int y1, int c = -1);

} // namespace clppm::test

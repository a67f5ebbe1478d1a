#include "test_util.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

#include "io/image_io.h"

namespace clppm::test {

DeviceInfo fake_device(int index, const std::string& platform, const std::string& name, cl_device_type type,
                       size_t global_mem, size_t max_alloc) {
    DeviceInfo d;
    d.index = index;
    d.platform_name = platform;
    d.name = name;
    d.type = type;
    d.global_mem = global_mem;
    d.max_alloc = max_alloc;
    return d;
}

const DeviceInfo& test_device() {
    static std::vector<DeviceInfo> devices = list_devices();
    if (devices.empty()) throw std::runtime_error("no OpenCL device for tests");
    if (const char* spec = std::getenv("CLPPM_TEST_DEVICE"); spec && *spec) return select_device(devices, spec);
    for (const DeviceInfo& d : devices)
        if (d.type & CL_DEVICE_TYPE_CPU) return d;
    return devices[0];
}

namespace {

// Every directory make_temp_dir hands out, removed after the last test of a binary that passed. A failing
// binary keeps them for inspection and says where; CLPPM_KEEP_TEST_DIRS=1 keeps them always. Before this,
// each run of the suite left about 1400 directories in /tmp.
class TempDirRegistry : public ::testing::Environment {
public:
    void add(const std::string& dir) {
        std::lock_guard<std::mutex> lock(mutex_);
        dirs_.push_back(dir);
    }
    void TearDown() override {
        std::lock_guard<std::mutex> lock(mutex_);
        const char* keep = std::getenv("CLPPM_KEEP_TEST_DIRS");
        if ((keep && *keep && std::string(keep) != "0") || !::testing::UnitTest::GetInstance()->Passed()) {
            if (!dirs_.empty())
                std::fprintf(stderr, "clppm tests: kept %zu temporary directories, e.g. %s\n", dirs_.size(),
                             dirs_.front().c_str());
            return;
        }
        for (const std::string& d : dirs_) {
            std::error_code ec;
            std::filesystem::remove_all(d, ec);
        }
        dirs_.clear();
    }

private:
    std::mutex mutex_;
    std::vector<std::string> dirs_;
};

TempDirRegistry* temp_dirs() {
    // gtest owns and deletes a registered environment.
    static TempDirRegistry* registry =
        static_cast<TempDirRegistry*>(::testing::AddGlobalTestEnvironment(new TempDirRegistry));
    return registry;
}

// Registered before main runs RUN_ALL_TESTS, so its TearDown follows the last test.
[[maybe_unused]] const TempDirRegistry* const registered_at_start = temp_dirs();

} // namespace

std::string make_temp_dir(const std::string& tag) {
    const char* base = std::getenv("TMPDIR");
    std::string tmpl = std::string(base && *base ? base : "/tmp") + "/clppm_test_" + tag + "_XXXXXX";
    std::vector<char> buf(tmpl.begin(), tmpl.end());
    buf.push_back('\0');
    if (!mkdtemp(buf.data())) throw std::runtime_error("mkdtemp failed for " + tmpl);
    temp_dirs()->add(buf.data());
    return buf.data();
}

int run_command(const std::string& cmd, std::string* output) {
    std::string full = cmd + " 2>&1";
    FILE* p = popen(full.c_str(), "r");
    if (!p) return -1;
    std::array<char, 4096> buf;
    std::string out;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
    int status = pclose(p);
    if (output) *output = out;
    if (WIFEXITED(status)) return WEXITSTATUS(status);
    if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
    return -1;
}

std::string clppm_binary() { return CLPPM_BINARY; }

int run_clppm(const std::string& args, std::string* output) { return run_command(clppm_binary() + " " + args, output); }

std::string expect_resume_is_exact(const std::string& args, const std::string& what) {
    std::string d = make_temp_dir("resume"), out;
    EXPECT_EQ(run_clppm(args + " --passes 5 -o " + d + "/full.exr", &out), 0) << what << ": " << out;
    EXPECT_EQ(run_clppm(args + " --passes 2 -o " + d + "/part.exr --checkpoint " + d + "/c.ck", &out), 0)
        << what << ": " << out;
    EXPECT_EQ(run_clppm(args + " --passes 5 -o " + d + "/res.exr --resume " + d + "/c.ck", &out), 0)
        << what << ": " << out;
    Image full = read_exr(d + "/full.exr"), res = read_exr(d + "/res.exr"), part = read_exr(d + "/part.exr");
    EXPECT_EQ(full.rgb, res.rgb) << what << ": resumed render differs";
    EXPECT_NE(full.rgb, part.rgb) << what << ": the test must compare different pass counts";
    return d;
}

} // namespace clppm::test

#include "io/image_io.h"

namespace clppm::test {

double render_test_scene_mean(const std::string& file, const std::string& integrator, int passes, int photons) {
    std::string d = make_temp_dir("scene_mean"), out;
    const std::string args = std::string(CLPPM_TEST_DATA) + "/" + file + " --width 48 --height 32 --passes " +
                             std::to_string(passes) + " --photons " + std::to_string(photons) +
                             " --quiet --no-png --integrator " + integrator + " -o " + d + "/i.exr";
    EXPECT_EQ(run_clppm(args, &out), 0) << out;
    EXPECT_EQ(out.find("warning"), std::string::npos) << out;
    return mean_radiance(read_exr(d + "/i.exr"));
}

std::array<double, 3> render_test_scene_channels(const std::string& file, const std::string& integrator, int passes,
                                                 int photons, int width, int height) {
    std::string d = make_temp_dir("scene_channels"), out;
    const std::string args = std::string(CLPPM_TEST_DATA) + "/" + file + " --width " + std::to_string(width) +
                             " --height " + std::to_string(height) + " --passes " + std::to_string(passes) +
                             " --photons " + std::to_string(photons) + " --quiet --no-png --integrator " + integrator +
                             " -o " + d + "/i.exr";
    EXPECT_EQ(run_clppm(args, &out), 0) << out;
    EXPECT_EQ(out.find("warning"), std::string::npos) << out;
    Image img = read_exr(d + "/i.exr");
    std::array<double, 3> m{0, 0, 0};
    for (size_t i = 0; i < img.rgb.size(); ++i) m[i % 3] += img.rgb[i];
    for (double& v : m) v /= double(img.rgb.size() / 3);
    return m;
}

void expect_scenes_render_alike(const std::string& file, const std::string& reference, double tolerance, int passes,
                                int photons) {
    for (const char* integrator : {"sppm", "pt"}) {
        SCOPED_TRACE(std::string(integrator) + ": " + file + " against " + reference);
        const double mean = render_test_scene_mean(file, integrator, passes, photons);
        const double want = render_test_scene_mean(reference, integrator, passes, photons);
        ASSERT_GT(want, 0);
        EXPECT_NEAR(mean / want, 1.0, tolerance);
    }
}

} // namespace clppm::test

#include "device/kernel_program.h"
#include "integrators/integrator_table.h"
#include "scene/device_scene.h"

namespace clppm::test {

Image render_passes(Scene scene, const RenderSettings& settings, uint64_t passes, IntegratorStats* stats) {
    DeviceContext dc(test_device());
    DeviceScene ds = upload_scene(dc, scene, settings);
    cl::Program program = build_program(dc, integrator_row(settings.integrator).program_file,
                                        integrator_build_options(settings, dc.info));
    std::unique_ptr<IntegratorBase> integ = make_integrator(dc, ds, settings, program);
    integ->prepare();
    for (uint64_t p = 0; p < passes; ++p) integ->run_pass();
    Image img = integ->image();
    if (stats) *stats = integ->stats();
    return img;
}

double region_mean(const Image& img, int x0, int y0, int x1, int y1, int c) {
    double sum = 0;
    size_t n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            for (int k = 0; k < 3; ++k) {
                if (c >= 0 && k != c) continue;
                sum += img.rgb[3 * (size_t(y) * img.width + x) + k];
                ++n;
            }
    return n ? sum / double(n) : 0.0;
}

std::string slurp(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

double time_scale() {
    const char* e = std::getenv("CLPPM_TEST_TIME_SCALE");
    const double s = e && *e ? std::strtod(e, nullptr) : 1.0;
    return s >= 1.0 ? s : 1.0;
}

cl::Program build_test_program(const DeviceContext& dc, const std::string& source) {
    cl::Program program(dc.context, source);
    try {
        program.build({dc.info.device}, "-cl-std=CL1.2");
    } catch (const cl::Error&) {
        ADD_FAILURE() << program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(dc.info.device);
        throw;
    }
    return program;
}

KernelHarness::KernelHarness(const std::string& source) : program(build_test_program(dc, source)) {}

} // namespace clppm::test

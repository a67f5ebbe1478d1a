// shading_simd: how fast one path vertex's shading runs on the device's OpenCL written as one path
// per work item (as the renderer's kernels are) and as explicit SIMD packets of 8 and 16 paths per
// work item. It bounds what tracing paths as vectors could gain on PoCL, whose compiler does not
// vectorise the renderer's kernels across work items (bench/RESULTS.md, issue 36).
//
//   shading_simd SCENE.gltf [--size N] [--reps N] [--rounds N] [--device SPEC]
//
// The scene (e.g. the diffuse Cornell box: python3 bench/cornell_diffuse.py scenes/cornell_box.gltf OUT.gltf)
// must hold Lambertian materials without textures and one or two emissive triangles as its only
// lights: the packet kernel (bench/shading_simd_vertex.cl) models nothing else. Camera rays through
// the pixel centres find the hits once; then each kernel shades every hit --reps times a round,
// the kernels taking turns for --rounds rounds, so that load from other processes hits all alike.
// Printed: the median wall and CPU nanoseconds per path vertex, and the largest difference between
// the widths' results (they do the same arithmetic, so it must stay at rounding level).
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_util.h"

namespace clppm::bench {
namespace {

double cpu_seconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

std::string read_text(const std::string& path) {
    std::ifstream f(path);
    if (!f) throw Error(path + ": cannot read");
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

// The vertex kernel at SIMD width w (1, 8 or 16).
std::string instantiate(const std::string& body, int w) {
    const std::string W = std::to_string(w);
    std::string d = "\n#define SIMD_W " + W + "u\n#define SIMD_NAME simd_probe_w" + W +
                    "\n#define SIMD_TRI simd_triangle_w" + W + "\n";
    if (w == 1) {
        d += "#define T float\n#define UT uint\n#define IT int\n#define LANES 0u\n"
             "#define LD(p, i) (p)[i]\n#define LDU(p, i) (p)[i]\n#define ST(p, i, v) ((p)[i] = (v))\n"
             "#define G(p, k) (p)[k]\n#define GU(p, k) (p)[k]\n#define CVT(x) ((float)(x))\n";
    } else {
        std::string lanes, gather;
        for (int j = 0; j < w; ++j) {
            lanes += (j ? ", " : "") + std::to_string(j) + "u";
            gather += std::string(j ? ", " : "") + "(p)[(k).s" + "0123456789abcdef"[j] + "]";
        }
        d += "#define T float" + W + "\n#define UT uint" + W + "\n#define IT int" + W + "\n#define LANES (UT)(" +
             lanes + ")\n#define LD(p, i) vload" + W + "(i, p)\n#define LDU(p, i) vload" + W +
             "(i, p)\n#define ST(p, i, v) vstore" + W + "(v, i, p)\n#define G(p, k) ((float" + W + ")(" + gather +
             "))\n#define GU(p, k) ((uint" + W + ")(" + gather + "))\n#define CVT(x) convert_float" + W + "(x)\n";
    }
    std::string u;
    for (const char* m :
         {"SIMD_W", "SIMD_NAME", "SIMD_TRI", "T", "UT", "IT", "LANES", "LD", "LDU", "ST", "G", "GU", "CVT"})
        u += std::string("#undef ") + m + "\n";
    return d + body + "\n" + u;
}

// The scene must be what the packet kernel models (see the top of this file): no kernel feature but
// area lights (so no specular layer, metal, glass, textures...), and one or two lights.
void check_scene(const Scene& scene, const DeviceScene& ds, const SceneFeatures& f) {
    SceneFeatures only_area;
    only_area.area_lights = true;
    if (feature_build_options(f) != feature_build_options(only_area))
        throw Error(scene.source + ": its kernels would need " + describe_features(f) +
                    "; the packet kernel models Lambertian surfaces (specularFactor 0) and area lights only");
    if (ds.lights.empty() || ds.lights.size() > 2)
        throw Error(scene.source + ": needs one or two lights, emissive triangles; it has " +
                    std::to_string(ds.lights.size()));
}

int run(int argc, char** argv) {
    std::string scene_path, device_spec;
    uint32_t size = 512;
    int reps = 20, rounds = 5;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw Error(a + ": needs a value");
            return argv[++i];
        };
        if (a == "--size") size = uint32_t(std::stoul(value()));
        else if (a == "--reps") reps = std::stoi(value());
        else if (a == "--rounds") rounds = std::stoi(value());
        else if (a == "--device") device_spec = value();
        else if (!a.empty() && a[0] == '-') throw Error(a + ": unknown option");
        else scene_path = a;
    }
    if (size < 16 || size > 4096 || size % 16) throw Error("--size: a multiple of 16 in 16..4096");
    if (reps < 1 || rounds < 1) throw Error("--reps and --rounds: at least 1");

    RenderSettings s;
    s.integrator = "pt";
    s.width = s.height = int(size);
    const DeviceInfo& device = bench_device(device_spec);
    DeviceContext dc(device);
    Scene scene = load_named_scene(scene_path);
    DeviceScene ds = upload_scene(dc, scene, s);
    const SceneFeatures features = scene_features(scene, ds);
    check_scene(scene, ds, features);
    const std::string dir = std::string(CLPPM_SOURCE_DIR) + "/bench/";
    const std::string vertex = read_text(dir + "shading_simd_vertex.cl");
    const std::string source = assemble_kernel_source("path_trace.cl") + "\n" + read_text(dir + "shading_simd.cl") +
                               instantiate(vertex, 1) + instantiate(vertex, 8) + instantiate(vertex, 16);
    const std::string options = "-cl-std=CL1.2 " + integrator_build_options(s, device, feature_build_options(features));
    cl::Program program(dc.context, source);
    try {
        program.build({device.device}, options.c_str());
    } catch (const cl::Error&) {
        throw Error("shading_simd: kernel build failed:\n" + program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device.device));
    }

    const uint32_t n = size * size;
    cl::Buffer soa(dc.context, CL_MEM_READ_WRITE, size_t(n) * 7 * sizeof(float));
    cl::Buffer hits(dc.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, sizeof(cl_uint),
                    std::vector<cl_uint>{0}.data());
    {
        cl::Kernel k(program, "simd_probe_hits");
        int a = ds.set_scene_args(k);
        k.setArg(a++, ds.camera_buf), k.setArg(a++, n), k.setArg(a++, soa), k.setArg(a++, hits);
        dc.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(n));
    }
    cl_uint hit_count = 0;
    dc.queue.enqueueReadBuffer(hits, CL_TRUE, 0, sizeof hit_count, &hit_count);

    struct Variant {
        const char* label;
        const char* kernel;
        uint32_t width;
        std::vector<double> wall, cpu;
        std::vector<float> result;
    };
    std::vector<Variant> variants = {
        {"renderer's code, one path per work item", "simd_probe_renderer", 1, {}, {}, {}},
        {"same work as the packets, one path per work item", "simd_probe_w1", 1, {}, {}, {}},
        {"float8 packets", "simd_probe_w8", 8, {}, {}, {}},
        {"float16 packets", "simd_probe_w16", 16, {}, {}, {}}};
    cl::Buffer out(dc.context, CL_MEM_READ_WRITE, size_t(n) * 3 * sizeof(float));
    const std::vector<float> zeros(size_t(n) * 3, 0.f);
    for (int round = 0; round <= rounds; ++round) { // round 0 warms up (the driver compiles lazily)
        for (Variant& v : variants) {
            cl::Kernel k(program, v.kernel);
            dc.queue.enqueueWriteBuffer(out, CL_TRUE, 0, zeros.size() * sizeof(float), zeros.data());
            const double w0 = now_s(), c0 = cpu_seconds();
            for (int r = 0; r < reps; ++r) {
                int a = ds.set_scene_args(k);
                k.setArg(a++, soa), k.setArg(a++, n), k.setArg(a++, cl_uint(r)), k.setArg(a++, out);
                dc.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(n / v.width));
            }
            dc.queue.finish();
            const double wall = now_s() - w0, cpu = cpu_seconds() - c0;
            if (round == 0) {
                v.result.resize(zeros.size());
                dc.queue.enqueueReadBuffer(out, CL_TRUE, 0, v.result.size() * sizeof(float), v.result.data());
                continue;
            }
            v.wall.push_back(1e9 * wall / (double(reps) * n));
            v.cpu.push_back(1e9 * cpu / (double(reps) * n));
        }
    }
    const auto median = [](std::vector<double> x) {
        std::sort(x.begin(), x.end());
        return x[x.size() / 2];
    };
    std::printf("# shading_simd: %s, %ux%u pixel-centre hits (%u real), %d launches a round, %d rounds\n",
                device.name.c_str(), size, size, hit_count, reps, rounds);
    std::printf("| kernel | wall ns per vertex | CPU ns per vertex | CPU time against one path per work item |\n");
    std::printf("|---|---:|---:|---:|\n");
    const double base = median(variants[1].cpu);
    for (const Variant& v : variants)
        std::printf("| %s | %.2f | %.2f | %.2f |\n", v.label, median(v.wall), median(v.cpu), median(v.cpu) / base);
    // The widths do the same arithmetic on the same numbers: their sums must agree to rounding.
    for (size_t j = 2; j < variants.size(); ++j) {
        double worst = 0;
        for (size_t e = 0; e < zeros.size(); ++e) {
            const double a = variants[1].result[e], b = variants[j].result[e];
            worst = std::max(worst, std::fabs(a - b) / std::max(1.0, std::fabs(a)));
        }
        std::printf("# largest relative difference, %s against one path per work item: %.2e\n", variants[j].label,
                    worst);
        if (!(worst < 1e-4)) throw Error("shading_simd: the packet kernel computes something else");
    }
    return 0;
}

} // namespace
} // namespace clppm::bench

int main(int argc, char** argv) {
    try {
        return clppm::bench::run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "shading_simd: error: %s\n", e.what());
        return 1;
    }
}

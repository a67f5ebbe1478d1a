// Vertex connection and merging and bidirectional path tracing (kernels/vcm.cl) against the path
// tracer and SPPM, technique by technique: each technique alone converges to the same image, the
// combinations agree with the independent integrators, and the render is reproducible.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include "device/kernel_launch.h"
#include "device/kernel_program.h"
#include "scene/gltf/gltf_load.h"
#include "scene_builders.h"
#include "test_util.h"
#include "vcm_mis.h"

using namespace clppm;
using namespace clppm::test;

namespace {

RenderSettings settings(const std::string& integrator, unsigned size, int techniques = -1) {
    RenderSettings s;
    s.width = s.height = size;
    s.integrator = integrator;
    s.vcm_techniques = techniques;
    s.photons = 20000; // SPPM
    return s;
}

size_t count_bad(const Image& img) {
    size_t n = 0;
    for (float v : img.rgb) n += !std::isfinite(v) || v < 0;
    return n;
}

// The means of img and ref agree within tol, and so do their quadrants' channels within qtol.
void expect_alike(const Image& img, const Image& ref, double tol, double qtol, const std::string& what) {
    EXPECT_EQ(count_bad(img), 0u) << what;
    EXPECT_NEAR(mean_radiance(img) / mean_radiance(ref), 1.0, tol) << what;
    const int h = img.width / 2;
    double worst = 0;
    for (int q = 0; q < 4; ++q)
        for (int c = 0; c < 3; ++c) {
            const int x0 = (q & 1) * h, y0 = (q >> 1) * h;
            worst = std::max(worst, std::fabs(region_mean(img, x0, y0, x0 + h, y0 + h, c) /
                                                  region_mean(ref, x0, y0, x0 + h, y0 + h, c) -
                                              1.0));
        }
    std::printf("%s: mean ratio %.4f, worst quadrant channel off by %.4f\n", what.c_str(),
                mean_radiance(img) / mean_radiance(ref), worst);
    for (int q = 0; q < 4; ++q) {
        const int x0 = (q & 1) * h, y0 = (q >> 1) * h;
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(region_mean(img, x0, y0, x0 + h, y0 + h, c) / region_mean(ref, x0, y0, x0 + h, y0 + h, c), 1.0,
                        qtol)
                << what << ": quadrant " << q << " channel " << c;
    }
}

// One of VCM's techniques alone (or all of them) against a reference: its mode, passes, the
// tolerances of expect_alike, the merging radius (0: the default) and a name.
struct TechniqueCase {
    int mode;
    uint64_t passes;
    double tol, qtol, radius;
    const char* name;
};

void expect_techniques_converge(const Scene& scene, const Image& ref, unsigned size,
                                const std::vector<TechniqueCase>& cases) {
    for (const TechniqueCase& c : cases) {
        RenderSettings s = settings("vcm", size, c.mode);
        s.radius = c.radius;
        expect_alike(render_passes(scene, s, c.passes), ref, c.tol, c.qtol, c.name);
    }
}

// The diffuse box under its area light, 24x24: the path tracer's image at 4096 passes.
const Image& diffuse_reference() {
    static const Image ref = render_passes(diffuse_box(), settings("pt", 24), 4096);
    return ref;
}

} // namespace

// Path tracing only, light tracing only, merging only, connections only (BPT) and all of them
// (VCM) each render the diffuse box as the independent path tracer does. Light tracing cannot see
// the light itself (no light vertex lies on it), so the image's lit part is compared: every
// technique counts directly seen emission (one way only to find it).
TEST(Vcm, EachTechniqueAloneConvergesToThePathTracersImage) {
    // Measured on the two-core PoCL box: ratios within 0.4% (mean) and 1.5% (quadrants). Merging
    // at 0.04, below the 24-pixel footprint (the default radius): little blur where it counts.
    expect_techniques_converge(diffuse_box(), diffuse_reference(), 24,
                               {TechniqueCase{VCM_MODE_PT, 2048, 0.015, 0.04, 0, "path tracing only"},
                                TechniqueCase{VCM_MODE_LT, 2048, 0.015, 0.04, 0, "light tracing only"},
                                TechniqueCase{VCM_MODE_VM, 512, 0.02, 0.05, 0.04, "merging only"},
                                TechniqueCase{VCM_MODE_BPT, 512, 0.01, 0.03, 0, "connections only (bpt)"},
                                TechniqueCase{VCM_MODE_VCM, 512, 0.01, 0.03, 0.04, "all (vcm)"}});
}

// The integrators as a user picks them: bpt and vcm against the path tracer on the diffuse box.
TEST(Vcm, BptAndVcmAgreeWithThePathTracerOnADiffuseBox) {
    const Image ref = render_passes(diffuse_box(), settings("pt", 48), 1024);
    expect_alike(render_passes(diffuse_box(), settings("bpt", 48), 256), ref, 0.01, 0.03, "bpt");
    expect_alike(render_passes(diffuse_box(), settings("vcm", 48), 256), ref, 0.01, 0.03, "vcm");
}

namespace {

// A caustic the path tracer cannot find: a point light above a glass sphere over a diffuse floor,
// in the box without its area light.
Scene caustic_box() {
    Scene s = diffuse_box(false);
    s.source = "<caustic box>";
    // Drop the area light (its two triangles, the last ones the builder added).
    s.positions.resize(s.positions.size() - 6);
    s.shading.resize(s.shading.size() - 2);
    uint32_t glass = add_material(s, 1, 1, 1, 0.f, false, MAT_GLASS, 1.5f, 0.f);
    add_sphere(s, {0.1f, -0.55f, -0.2f}, 0.4f, 24, 48, glass);
    add_point_light(s, {0.1f, 0.8f, -0.2f}, 3.0f);
    return s;
}

} // namespace

// Vcm against SPPM where caustics matter: a point light's caustic through a glass sphere.
TEST(Vcm, AgreesWithSppmOnACausticScene) {
    const Scene scene = caustic_box();
    Image sppm = render_passes(scene, settings("sppm", 32), 256);
    Image vcm = render_passes(scene, settings("vcm", 32), 384);
    EXPECT_EQ(count_bad(vcm), 0u);
    // Measured: 0.998 (mean); the caustic's own region within 2%.
    EXPECT_NEAR(mean_radiance(vcm) / mean_radiance(sppm), 1.0, 0.01);
    EXPECT_NEAR(region_mean(vcm, 8, 20, 24, 32) / region_mean(sppm, 8, 20, 24, 32), 1.0, 0.04);
}

TEST(Vcm, TheSameSeedGivesTheSameImageBitForBit) {
    for (std::string integ : {"vcm", "bpt"}) {
        RenderSettings s = settings(integ, 20);
        Image a = render_passes(diffuse_box(), s, 3), b = render_passes(diffuse_box(), s, 3);
        ASSERT_EQ(a.rgb.size(), b.rgb.size());
        EXPECT_EQ(0, std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float))) << integ;
        s.seed = 2;
        Image c = render_passes(diffuse_box(), s, 3);
        EXPECT_NE(0, std::memcmp(a.rgb.data(), c.rgb.data(), a.rgb.size() * sizeof(float))) << integ;
    }
}

// Light sub-paths traced in batches (as when their vertices do not fit the device) give the
// same image: the camera sub-paths are the same in every batch and each technique counts once.
TEST(Vcm, BatchesOfLightSubPathsGiveTheSameImage) {
    RenderSettings s = settings("vcm", 20);
    IntegratorStats one, many;
    Image a = render_passes(diffuse_box(), s, 2, &one);
    setenv("CLPPM_PHOTON_BATCH", "37", 1);
    Image b = render_passes(diffuse_box(), s, 2, &many);
    unsetenv("CLPPM_PHOTON_BATCH");
    EXPECT_EQ(one.photons_stored, many.photons_stored);
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    // Equal up to the order doubles are added in (batches are summed one by one).
    for (size_t i = 0; i < a.rgb.size(); ++i) EXPECT_NEAR(b.rgb[i], a.rgb[i], 1e-5 * (1 + a.rgb[i])) << i;
}

// Light power and scene size do not change the image beyond scaling it: the light side is kept in
// units of total power and scene-relative areas.
TEST(Vcm, ExactAtExtremeLightPowerAndSceneScale) {
    const RenderSettings s = settings("vcm", 16);
    const Image base = render_passes(diffuse_box(), s, 8);
    for (double scale : {1e-4, 1e4}) {
        Scene scene = diffuse_box();
        for (Vec3& p : scene.positions) p = {float(p.x * scale), float(p.y * scale), float(p.z * scale)};
        for (CameraDesc& c : scene.cameras)
            for (float& x : c.position) x = float(x * scale);
        Image img = render_passes(scene, s, 8);
        EXPECT_EQ(count_bad(img), 0u) << scale;
        EXPECT_NEAR(mean_radiance(img) / mean_radiance(base), 1.0, 1e-3) << "scene scale " << scale;
    }
    for (float power : {1e-20f, 1e20f}) {
        Scene scene = diffuse_box();
        for (auto& m : scene.materials)
            for (int k = 0; k < 3; ++k) m.emission[k] *= power;
        Image img = render_passes(scene, s, 8);
        EXPECT_EQ(count_bad(img), 0u) << power;
        EXPECT_NEAR(mean_radiance(img) / (mean_radiance(base) * power), 1.0, 1e-3) << "light power " << power;
    }
}

namespace {

const char* kCameraWrappers = R"CL(
/* For each (px, py) in xy: the ray camera_ray makes, then where camera_project puts the point one
 * unit along it: pixel, cos_theta, and the pixel's density camera_pixel_pdf_w. */
__kernel void project_back(__constant Camera* cam, __global const float2* xy, __global float4* out, uint n) {
    uint i = get_global_id(0);
    if (i >= n) return;
    float3 o, d;
    float2 t = (float2)(xy[i].x * 0.618f, xy[i].y * 0.382f), lens = t - floor(t);
    camera_ray(cam, xy[i].x, xy[i].y, lens, &o, &d);
    uint pixel = 0xffffffffu;
    float c = -1.0f;
    float3 eye;
    bool ok = camera_project(cam, o + d * 3.0f, lens, &pixel, &c, &eye) && length(eye - o) < 1e-5f;
    out[i] = (float4)(ok ? (float)pixel : -1.0f, c, camera_pixel_pdf_w(cam, c), dot(d, load3c(cam->forward)));
}
)CL";

dev::Camera test_camera(unsigned w, unsigned h, float lens_radius) {
    dev::Camera c{};
    c.lens_radius = lens_radius;
    c.focus_distance = 2.0f;
    c.origin[0] = 0.3f, c.origin[1] = -0.2f, c.origin[2] = 1.5f;
    // Looking along a tilted axis, with a frame orthogonal to it.
    const D3 f = normalized(D3{0.2, -0.1, -1}), r = normalized(cross(f, D3{0, 1, 0})), u = cross(r, f);
    const double tx = std::tan(0.6), ty = tx * h / w;
    for (int k = 0; k < 3; ++k) {
        c.forward[k] = float((&f.x)[k]);
        c.right[k] = float((&r.x)[k] * tx);
        c.up[k] = float((&u.x)[k] * ty);
    }
    c.width = w, c.height = h;
    return c;
}

} // namespace

// Light tracing's link to the camera: camera_project inverts camera_ray (same pixel, same cosine,
// the same lens point for a thin lens),
// and camera_pixel_pdf_w is a density over each pixel's solid angle: 1 / (area on the image plane
// at distance 1 times cos^3), integrated here on the host by the solid angle of sub-pixel cells.
TEST(Vcm, TheCameraProjectionInvertsItsRaysAndItsPixelDensityIntegratesToOne) {
    KernelHarness d(assemble_kernel_source("camera.cl") + kCameraWrappers);
    const unsigned w = 37, h = 23;
    for (float lens_radius : {0.0f, 0.1f}) {
        const dev::Camera cam = test_camera(w, h, lens_radius);
        std::vector<cl_float2> xy;
        for (unsigned py = 0; py < h; ++py)
            for (unsigned px = 0; px < w; ++px)
                xy.push_back({{float(px) + 0.25f + 0.5f * float((px * 7 + py) % 3) / 3,
                               float(py) + 0.3f + 0.4f * float((py * 5 + px) % 4) / 4}});
        cl::Buffer cb = d.input(std::vector<dev::Camera>{cam}), in = d.input(xy), out = d.output(xy.size() * 16);
        cl::Kernel k(d.program, "project_back");
        set_args(k, 0, cb, in, out, cl_uint(xy.size()));
        d.run(k, xy.size());
        const std::vector<cl_float4> r = d.read<cl_float4>(out, xy.size());
        for (size_t i = 0; i < xy.size(); ++i) {
            EXPECT_EQ(r[i].s[0], float(i)) << "pixel " << i << " lens " << lens_radius;
            EXPECT_NEAR(r[i].s[1], r[i].s[3], 1e-5) << "cos " << i;
        }
        if (lens_radius > 0) continue; // the density does not depend on the lens (camera.cl)
        // The density times each sub-cell's solid angle (host geometry, in double) sums to 1 per pixel.
        const D3 f = d3(cam.forward), rt = d3(cam.right), up = d3(cam.up);
        for (size_t i : {size_t(0), size_t(w * h / 2 + 3), size_t(w * h - 1)}) {
            const unsigned px = unsigned(i % w), py = unsigned(i / w);
            const int sub = 64;
            double sum = 0;
            for (int a = 0; a < sub; ++a)
                for (int b = 0; b < sub; ++b) {
                    const double sx = 2 * (px + (a + 0.5) / sub) / w - 1, sy = 1 - 2 * (py + (b + 0.5) / sub) / h;
                    const D3 q = f + rt * sx + up * sy;
                    const double cell = (2 * length(rt) / w / sub) * (2 * length(up) / h / sub);
                    const double cos_t = dot(normalized(q), f), dist2 = dot(q, q);
                    const double omega = cell * cos_t / dist2; // the cell's solid angle
                    const double pdf = 1.0 / ((4 * length(rt) * length(up) / (w * h)) * cos_t * cos_t * cos_t);
                    sum += pdf * omega;
                }
            EXPECT_NEAR(sum, 1.0, 1e-6) << "pixel " << i;
        }
        // And the kernel's density is that formula.
        const size_t i = w * h / 2 + 3;
        const double c = r[i].s[1];
        EXPECT_NEAR(r[i].s[2] * (4 * length(rt) * length(up) / (w * h)) * c * c * c, 1.0, 1e-5);
    }
}

// Depth of field: light sub-paths reach the image through the lens as camera sub-paths leave it.
TEST(Vcm, ThinLensAgreesWithThePathTracer) {
    RenderSettings pt = settings("pt", 32), vcm = settings("vcm", 32);
    pt.aperture = vcm.aperture = 0.08;
    pt.focus_distance = vcm.focus_distance = 1.2;
    const Image ref = render_passes(diffuse_box(), pt, 1024);
    vcm.vcm_techniques = VCM_MODE_LT; // light tracing alone: the lens mapping carries everything
    expect_alike(render_passes(diffuse_box(), vcm, 1024), ref, 0.015, 0.04, "thin lens, light tracing only");
    vcm.vcm_techniques = -1;
    expect_alike(render_passes(diffuse_box(), vcm, 256), ref, 0.01, 0.03, "thin lens, vcm");
}

namespace {

const char* kFixedWrappers = R"CL(
__kernel void add_all(__global const long* v, uint n, uint slots, volatile __global long* sums) {
    uint i = get_global_id(0);
    if (i < n) add_fixed(&sums[i % slots], v[i]);
}
)CL";

} // namespace

// The splat image's sums (kernels/fixed_point.cl), with 64-bit atomics and with the two 32-bit
// words the kernels fall back on without them, against the host's sum: exact, carries and signs
// included.
TEST(Vcm, FixedPointSumsAreExactWithOrWithoutInt64Atomics) {
    std::mt19937_64 rng(5);
    const uint32_t n = 200000, slots = 7;
    std::vector<cl_long> v(n);
    std::vector<int64_t> want(slots, 0);
    for (uint32_t i = 0; i < n; ++i) {
        // Mixed magnitudes: low words that carry, negative values that borrow.
        v[i] = int64_t(rng() >> (i % 3 == 0 ? 24 : 40)) * (i % 5 == 0 ? -1 : 1);
        want[i % slots] += v[i];
    }
    for (const char* prefix : {"", "#define CLPPM_NO_INT64_ATOMICS\n"}) {
        KernelHarness d(std::string(prefix) + assemble_kernel_source("fixed_point.cl") + kFixedWrappers);
        cl::Buffer in = d.input(v), sums = d.input(std::vector<cl_long>(slots, 0));
        cl::Kernel k(d.program, "add_all");
        set_args(k, 0, in, cl_uint(n), cl_uint(slots), sums);
        d.run(k, n);
        const std::vector<cl_long> got = d.read<cl_long>(sums, slots);
        for (uint32_t s = 0; s < slots; ++s) EXPECT_EQ(got[s], want[s]) << (*prefix ? "32-bit words" : "int64") << s;
    }
}

// Through a rough glass block (tests/data/ref_rough_glass.gltf), where VCM merges and connects at
// the glass's own surfaces, inside it too: a camera vertex inside the block carries radiance, whose
// refraction is 1/eta^2 of the importance a light sub-path carries (kernels/bsdf.cl, transport).
// With one BSDF for both, merging alone was 10 to 25% too bright here and BPT 1.3%.
TEST(Vcm, EachTechniqueAloneConvergesThroughRoughGlass) {
    const Scene scene = load_gltf(std::string(CLPPM_TEST_DATA) + "/ref_rough_glass.gltf");
    // Measured on the two-core PoCL box: merging alone 0.994 (worst quadrant channel 3.3% off),
    // BPT 1.0011 (0.6%), all together 1.009 (2.3%) at radius 0.03. All together carry merging's
    // bias, which grows with the radius: 1.028 at the default radius of these 32 pixels, 1.044 at
    // 0.2 (6% at the default before the transport modes).
    expect_techniques_converge(scene, render_passes(scene, settings("pt", 32), 4096), 32,
                               {TechniqueCase{VCM_MODE_VM, 2048, 0.03, 0.07, 0, "merging only"},
                                TechniqueCase{VCM_MODE_BPT, 1024, 0.01, 0.02, 0, "connections only (bpt)"},
                                TechniqueCase{VCM_MODE_VCM, 1024, 0.02, 0.045, 0.03, "all (vcm)"}});
}

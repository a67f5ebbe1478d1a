// kernels/lights.cl on the device with real scene buffers (upload_scene): emit_photon for 1M
// photons from a scene with emissive triangles of different areas and radiances (one
// two-sided, one RGB), a point, a spot and a directional light, and sample_light at a few
// points. Against host references: the light each photon came from is found from its geometry
// (not from the kernel's random numbers), power and irradiance are computed independently
// (Le A pi per side, 4 pi I, 2 pi I times the glTF cone integral, E pi R^2; Lambert's polygon
// formula for the irradiance from a triangle).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numeric>
#include <random>

#include "device/kernel_program.h"
#include "photon_emission.h"
#include "scene/device_scene.h"
#include "scene_builders.h"
#include "stat_tests.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

const char* kWrappers = R"CL(
/* SAMPLES sample_light calls per work item at x with normal n: the sums of (contrib * max(0, cos_x)).rgb
 * and of their squares, and the smallest shadow-ray distance of a sample that counted. */
#define SAMPLES 16
__kernel void sample_light_many(SCENE_PARAMS, ulong seed, float px, float py, float pz, float nx, float ny, float nz,
                                __global double* out) {
    uint i = get_global_id(0);
    Rng rng = rng_make(seed, 1, i, RNG_DIRECT);
    float3 x = (float3)(px, py, pz), n = (float3)(nx, ny, nz);
    double3 sum = (double3)(0.0), sum_sq = (double3)(0.0);
    double min_dist = INFINITY;
    for (int k = 0; k < SAMPLES; ++k) {
        float3 wi, c;
        float dist = 0.0f, pdf;
        if (!sample_light(SCENE_ARGS, x, &rng, &wi, &dist, &c, &pdf)) continue;
        double3 e = convert_double3(c * fmax(0.0f, dot(wi, n)));
        sum += e;
        sum_sq += e * e;
        min_dist = fmin(min_dist, (double)dist);
    }
    __global double* o = &out[7 * (size_t)i];
    o[0] = sum.x; o[1] = sum.y; o[2] = sum.z; o[3] = sum_sq.x; o[4] = sum_sq.y; o[5] = sum_sq.z; o[6] = min_dist;
}
/* pick_light_reuse for the uniforms u[3 i .. 3 i + 2] (u.x, u.y, u_spare): the light, and the pair
 * it leaves for the light's point. */
__kernel void pick_reuse_many(SCENE_PARAMS, float share, __global const float* u, __global float* out) {
    uint i = get_global_id(0);
    float2 uv = (float2)(u[3 * i], u[3 * i + 1]);
    uint l = pick_light_reuse(SCENE_ARGS, share, &uv, u[3 * i + 2]);
    out[3 * i] = (float)l; out[3 * i + 1] = uv.x; out[3 * i + 2] = uv.y;
}
)CL";

// The scene: three emissive triangles (areas 0.5, 0.125, 2; radiance 2, RGB (5, 3, 1) two-sided,
// 0.5 on a tilted plane), a point light, a spot light (cones 0.3 / 0.5 rad) and a directional
// light, over a non-emissive floor.
constexpr float kSpotI = 20.f, kSpotInner = 0.3f, kSpotOuter = 0.5f, kPointI = 3.f, kSunE = 1.5f;
const D3 kSunDir = normalized({0.3, -1, 0.2});
Scene emission_scene() {
    Scene s;
    s.source = "<emission test>";
    uint32_t floor = add_material(s, 0.5f, 0.5f, 0.5f);
    uint32_t a = add_material(s, 0, 0, 0, 2.f);
    uint32_t b = add_material(s, 0, 0, 0, 0.f, true);
    s.materials[b].emission[0] = 5, s.materials[b].emission[1] = 3, s.materials[b].emission[2] = 1;
    uint32_t c = add_material(s, 0, 0, 0, 0.5f);
    add_quad(s, {-2, -1, -2}, {-2, -1, 2}, {2, -1, 2}, {2, -1, -2}, floor);
    // A: in the plane y = 1, facing down (counter-clockwise seen from below).
    add_triangle(s, {-1.5f, 1, -1.5f}, {-0.5f, 1, -1.5f}, {-1.5f, 1, -0.5f}, a);
    // B: a small vertical triangle in the plane z = 1, both faces emit.
    add_triangle(s, {1, 0, 1}, {1.5f, 0, 1}, {1, 0.5f, 1}, b);
    // C: on a tilted plane through (0.5, 0.2, -1).
    add_triangle(s, {0.5f, 0.2f, -1.f}, {2.5f, 0.2f, -1.f}, {0.5f, 1.2f, -2.7320508f}, c);
    add_point_light(s, {0, 0.5f, 0}, kPointI);
    add_spot_light(s, {1, 2, 0}, kSpotI, kSpotInner, kSpotOuter);
    add_directional_light(s, {float(kSunDir.x), float(kSunDir.y), float(kSunDir.z)}, kSunE);
    return s;
}

// glTF KHR_lights_punctual's spot attenuation, integrated over the cone: 2 pi I times
// int_{cos_outer}^{1} falloff(c) dc, falloff = clamp((c - co) / (ci - co), 0, 1)^2.
double spot_falloff(double c, double ci, double co) {
    double a = std::clamp((c - co) / (ci - co), 0.0, 1.0);
    return a * a;
}
double spot_power(double I, double ci, double co) { return 2 * M_PI * I * ((1 - ci) + (ci - co) / 3); }

enum class Kind { Triangle, Point, Spot, Directional };
struct HostLight {
    Kind kind;
    size_t index;     // in ds.lights
    D3 v0, e1, e2, n; // triangles: vertices and the winding normal
    double area = 0;
    bool two_sided = false;
    D3 rgb{0, 0, 0};  // Le, I or E
    double power = 0; // the true emitted power (mean over RGB)
    D3 power_rgb{0, 0, 0};
    D3 position{0, 0, 0}, direction{0, 0, 0};
};

// Host description of every light of ds.lights, from the (BVH-reordered) scene itself.
std::vector<HostLight> describe_lights(const Scene& scene, const DeviceScene& ds) {
    std::vector<HostLight> lights;
    const double R = ds.info.radius;
    for (size_t i = 0; i < ds.lights.size(); ++i) {
        const dev::Light& L = ds.lights[i];
        HostLight h;
        h.index = i;
        if (L.type == LIGHT_TRIANGLE) {
            h.kind = Kind::Triangle;
            D3 p0 = d3(scene.positions[3 * L.prim]), p1 = d3(scene.positions[3 * L.prim + 1]),
               p2 = d3(scene.positions[3 * L.prim + 2]);
            h.v0 = p0, h.e1 = p1 - p0, h.e2 = p2 - p0;
            D3 c = cross(h.e1, h.e2);
            h.area = 0.5 * length(c);
            h.n = normalized(c);
            const dev::Material& m = scene.materials[scene.shading[L.prim].material];
            h.two_sided = (m.flags & MATERIAL_FLAG_DOUBLE_SIDED) != 0;
            h.rgb = d3(m.emission);
            h.power_rgb = (h.area * M_PI * (h.two_sided ? 2 : 1)) * h.rgb;
        } else if (L.type == LIGHT_POINT) {
            h.kind = Kind::Point;
            h.position = d3(L.position);
            h.rgb = d3(L.radiance);
            h.power_rgb = (4 * M_PI) * h.rgb;
        } else if (L.type == LIGHT_SPOT) {
            h.kind = Kind::Spot;
            h.position = d3(L.position), h.direction = d3(L.direction);
            h.rgb = d3(L.radiance);
            h.power_rgb = (spot_power(1, std::cos(double(kSpotInner)), std::cos(double(kSpotOuter)))) * h.rgb;
        } else {
            h.kind = Kind::Directional;
            h.direction = d3(L.direction);
            h.rgb = d3(L.radiance);
            h.power_rgb = (M_PI * R * R) * h.rgb;
        }
        h.power = (h.power_rgb.x + h.power_rgb.y + h.power_rgb.z) / 3;
        lights.push_back(h);
    }
    return lights;
}

struct Fixture {
    DeviceContext dc{test_device()};
    Scene scene = emission_scene();
    DeviceScene ds;
    cl::Program program;
    std::vector<HostLight> lights;
    std::vector<float> photons; // 9 floats each
    std::vector<int> source;    // index into `lights` found from each photon's geometry, -1 if none
    static constexpr size_t kPhotons = 1000000;

    Fixture()
        : ds(upload_scene(dc, scene, RenderSettings{})),
          program(build_test_program(dc, assemble_kernel_source("rng.cl") + assemble_kernel_source("lights.cl") +
                                             kEmitManyKernel + kWrappers)) {
        lights = describe_lights(scene, ds);
        emit();
    }

    template <class T>
    std::vector<T> read(const cl::Buffer& b, size_t n) const {
        return read_buffer<T>(dc, b, n);
    }

    // Which light a photon left: punctual lights by origin, the directional one by direction,
    // triangles by lying (up to the ray offset) on the triangle.
    int identify(const float* p) const {
        D3 org = d3(p), dir = d3(p + 3);
        const double m = std::max({std::fabs(org.x), std::fabs(org.y), std::fabs(org.z)});
        const double offset = ds.info.ray_eps + 4e-6 * m; // offset_origin's, kernels/scene.cl
        for (size_t i = 0; i < lights.size(); ++i) {
            const HostLight& h = lights[i];
            if ((h.kind == Kind::Point || h.kind == Kind::Spot) && length(org - h.position) < 1e-6) return int(i);
            if (h.kind == Kind::Directional && length(dir - h.direction) < 1e-6) return int(i);
            if (h.kind == Kind::Triangle) {
                double dist = dot(org - h.v0, h.n);
                if (std::fabs(std::fabs(dist) - offset) > 1e-3 * offset + 1e-6) continue;
                double b1, b2;
                barycentrics(h, org, &b1, &b2);
                if (b1 >= -1e-5 && b2 >= -1e-5 && b1 + b2 <= 1 + 1e-5) return int(i);
            }
        }
        return -1;
    }
    static void barycentrics(const HostLight& h, D3 p, double* b1, double* b2) {
        D3 q = p - h.v0;
        double d11 = dot(h.e1, h.e1), d12 = dot(h.e1, h.e2), d22 = dot(h.e2, h.e2), q1 = dot(q, h.e1),
               q2 = dot(q, h.e2);
        double det = d11 * d22 - d12 * d12;
        *b1 = (d22 * q1 - d12 * q2) / det;
        *b2 = (d11 * q2 - d12 * q1) / det;
    }

    void emit() {
        photons = emit_photons(dc, ds, program, 99, kPhotons);
        source.resize(kPhotons);
        for (size_t i = 0; i < kPhotons; ++i) source[i] = identify(&photons[9 * i]);
    }

    // sample_light at x (normal n) on scene `on`: per channel the mean of contrib * cos and its
    // standard error over items * 16 samples; *min_dist the smallest shadow distance returned.
    std::vector<MeanSe> sample_light(const DeviceScene& on, D3 x, D3 n, size_t items, double* min_dist) const {
        cl::Buffer out(dc.context, CL_MEM_WRITE_ONLY, 7 * items * sizeof(double));
        cl::Kernel k(program, "sample_light_many");
        int a = on.set_scene_args(k);
        k.setArg(a++, cl_ulong(5));
        k.setArg(a++, float(x.x)), k.setArg(a++, float(x.y)), k.setArg(a++, float(x.z));
        k.setArg(a++, float(n.x)), k.setArg(a++, float(n.y)), k.setArg(a++, float(n.z));
        k.setArg(a++, out);
        dc.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(items));
        std::vector<double> v = read<double>(out, 7 * items);
        std::vector<MeanSe> r;
        *min_dist = INFINITY;
        for (int c = 0; c < 3; ++c) {
            double sum = 0, sum_sq = 0;
            for (size_t i = 0; i < items; ++i) sum += v[7 * i + c], sum_sq += v[7 * i + 3 + c];
            r.push_back(mean_se(sum, sum_sq, 16.0 * items));
        }
        for (size_t i = 0; i < items; ++i) *min_dist = std::min(*min_dist, v[7 * i + 6]);
        return r;
    }

    std::vector<size_t> photons_of(size_t light) const {
        std::vector<size_t> v;
        for (size_t i = 0; i < kPhotons; ++i)
            if (source[i] == int(light)) v.push_back(i);
        return v;
    }
};

Fixture& fixture() {
    static Fixture f;
    return f;
}

const double kAlpha = sidak(1e-3, 16); // per chi-square test of this program

std::string name(const HostLight& h) {
    const char* k[] = {"triangle", "point", "spot", "directional"};
    return std::string(k[int(h.kind)]) + " light " + std::to_string(h.index);
}

// Irradiance at x (normal n) from a Lambertian polygon of radiance L: Lambert's formula
// E = L / 2 * |sum_i theta_i n . normalize(r_i x r_i+1)| for the polygon clipped to x's upper
// half space (Sutherland-Hodgman against the tangent plane).
double polygon_irradiance(D3 x, D3 n, std::vector<D3> poly, double L) {
    std::vector<D3> clipped;
    for (size_t i = 0; i < poly.size(); ++i) {
        D3 a = poly[i], b = poly[(i + 1) % poly.size()];
        double da = dot(a - x, n), db = dot(b - x, n);
        if (da > 0) clipped.push_back(a);
        if ((da > 0) != (db > 0)) clipped.push_back(a + (da / (da - db)) * (b - a));
    }
    if (clipped.size() < 3) return 0;
    double sum = 0;
    for (size_t i = 0; i < clipped.size(); ++i) {
        D3 r0 = normalized(clipped[i] - x), r1 = normalized(clipped[(i + 1) % clipped.size()] - x);
        D3 c = cross(r0, r1);
        double s = length(c);
        if (s == 0) continue;
        sum += std::atan2(s, dot(r0, r1)) * dot(n, (1.0 / s) * c);
    }
    return 0.5 * L * std::fabs(sum);
}

} // namespace

// Every photon comes from exactly one light, recognised from its geometry.
TEST(LightEmission, EveryPhotonLeavesALight) {
    Fixture& f = fixture();
    ASSERT_EQ(f.lights.size(), 6u);
    size_t unknown = 0;
    for (int s : f.source) unknown += s < 0;
    EXPECT_EQ(unknown, 0u);
}

// Lights are chosen in proportion to the power the host assigned them (Light.power, the CDF):
// chi-square over the six lights.
TEST(LightEmission, LightsArePickedInProportionToPower) {
    Fixture& f = fixture();
    std::vector<double> observed(f.lights.size(), 0), expected(f.lights.size(), 0);
    for (int s : f.source)
        if (s >= 0) observed[s] += 1;
    for (size_t i = 0; i < f.lights.size(); ++i)
        expected[i] = Fixture::kPhotons * f.ds.lights[i].power / f.ds.info.total_power;
    Chi2Result c = chi2_test(observed, expected);
    EXPECT_GT(c.p_value, kAlpha) << "chi2 " << c.chi2 << " dof " << c.dof;
    double total = 0;
    for (const dev::Light& l : f.ds.lights) total += l.power;
    EXPECT_NEAR(f.ds.info.total_power / total, 1.0, 1e-6);
}

// Light.power is documented as the light's power in watts (mean over RGB), and drives both the
// pick probability and SceneInfo.total_power. Each must equal the power the light actually
// emits: Le A pi per emitting side, 4 pi I, for a spot 2 pi I ((1 - cos_inner) + (cos_inner -
// cos_outer) / 3) under glTF's squared falloff (the integral of clamp((c - co)/(ci - co))^2 dc),
// E pi R^2 for the directional light's disc. Relative 1e-5: float storage of the power.
// This test found collect_lights (src/scene/device_scene.cpp) storing the linear ramp's integral,
// 2 pi I (1 - (ci + co) / 2), for spots: images stayed unbiased (the photon flux divides by the
// same pick probability) but light selection over-weighted spots by 18% here.
TEST(LightEmission, LightPowerIsTheEmittedPower) {
    Fixture& f = fixture();
    for (const HostLight& h : f.lights)
        EXPECT_NEAR(f.ds.lights[h.index].power / h.power, 1.0, 1e-5)
            << name(h) << ": stored " << f.ds.lights[h.index].power << " W, emits " << h.power << " W";
}

// The flux photons carry adds up to each light's true power, per channel: sum over photons of
// flux * total_power / N (kernels/lights.cl: flux in units of SceneInfo.total_power). Tolerance:
// 5 standard errors of that mean, estimated from the photons themselves, plus 1e-5 relative
// (float flux).
TEST(LightEmission, EmittedFluxSumsToEachLightsPower) {
    Fixture& f = fixture();
    const double P = f.ds.info.total_power, N = double(Fixture::kPhotons);
    D3 total{0, 0, 0}, total_expected{0, 0, 0};
    for (const HostLight& h : f.lights) {
        for (int c = 0; c < 3; ++c) {
            double sum = 0, sum_sq = 0;
            for (size_t i : f.photons_of(h.index)) {
                double x = f.photons[9 * i + 6 + c] * P;
                sum += x, sum_sq += x * x;
            }
            MeanSe m = mean_se(sum, sum_sq, N);
            double want = c == 0 ? h.power_rgb.x : c == 1 ? h.power_rgb.y : h.power_rgb.z;
            EXPECT_NEAR(m.mean, want, 5 * m.se + 1e-5 * want) << name(h) << " channel " << c;
            (c == 0 ? total.x : c == 1 ? total.y : total.z) += m.mean;
            (c == 0 ? total_expected.x : c == 1 ? total_expected.y : total_expected.z) += want;
        }
    }
    // Uniform emitters give every photon of a light the same flux: Le A pi sides / (pick P) for
    // triangles, 4 pi I / (pick P) for the point light, E pi R^2 / (pick P) for the sun.
    for (const HostLight& h : f.lights) {
        if (h.kind == Kind::Spot) continue;
        double pick = f.ds.lights[h.index].power / P;
        double want = h.power_rgb.x / (pick * P);
        for (size_t i : f.photons_of(h.index)) ASSERT_NEAR(f.photons[9 * i + 6] / want, 1.0, 1e-5) << name(h);
    }
    std::printf("emitted power: %.5g %.5g %.5g W, lights: %.5g %.5g %.5g W\n", total.x, total.y, total.z,
                total_expected.x, total_expected.y, total_expected.z);
}

// Points on each emissive triangle are uniform by area: barycentrics in an 8 x 8 grid (inside
// cells expect 2 h^2 of the photons, diagonal cells h^2), chi-square; and every origin sits
// offset_origin's distance off the plane on the side it emits from.
TEST(LightEmission, TrianglePointsAreUniformByArea) {
    Fixture& f = fixture();
    for (const HostLight& h : f.lights) {
        if (h.kind != Kind::Triangle) continue;
        std::vector<size_t> ids = f.photons_of(h.index);
        ASSERT_GT(ids.size(), 10000u) << name(h);
        const int g = 8;
        const double cell = 1.0 / g;
        std::vector<double> observed(g * g, 0), expected(g * g, 0);
        for (int i = 0; i < g; ++i)
            for (int j = 0; j < g; ++j)
                expected[i * g + j] = ids.size() * 2 *
                                      (i + j < g - 1    ? cell * cell
                                       : i + j == g - 1 ? cell * cell / 2
                                                        : 0);
        for (size_t id : ids) {
            D3 org = d3(&f.photons[9 * id]), dir = d3(&f.photons[9 * id + 3]);
            double side = dot(org - h.v0, h.n);
            ASSERT_GT(side * dot(dir, h.n), 0.0) << name(h) << ": the photon leaves from the side it is offset to";
            D3 on_plane = org - side * h.n;
            double b1, b2;
            Fixture::barycentrics(h, on_plane, &b1, &b2);
            int i = std::clamp(int(b1 * g), 0, g - 1), j = std::clamp(int(b2 * g), 0, g - 1);
            observed[i * g + j] += 1;
        }
        Chi2Result c = chi2_test(observed, expected);
        EXPECT_TRUE(c.error.empty()) << name(h) << ": " << c.error;
        EXPECT_GT(c.p_value, kAlpha) << name(h) << ": chi2 " << c.chi2 << " dof " << c.dof;
    }
}

// Directions leave each triangle cosine-distributed about the emitting side's normal: single-sided
// triangles never emit from the back; two-sided ones emit half their photons from each side
// (binomial, 5 sigma). Chi-square in (cos theta, phi) about the side's normal, 10 x 8 bins.
TEST(LightEmission, TriangleDirectionsAreCosineAboutTheEmittingSide) {
    Fixture& f = fixture();
    for (const HostLight& h : f.lights) {
        if (h.kind != Kind::Triangle) continue;
        std::vector<size_t> ids = f.photons_of(h.index);
        size_t back = 0;
        SphereBins bins{10, 8, 0, 1};
        std::vector<double> observed(bins.size(), 0);
        D3 t, b;
        host_frame(h.n, t, b);
        for (size_t id : ids) {
            D3 dir = d3(&f.photons[9 * id + 3]);
            double c = dot(dir, h.n);
            D3 side_n = h.n;
            if (c < 0) ++back, c = -c, side_n = -1.0 * h.n;
            // Fold the back side onto the front (phi mirrored, which a cosine lobe does not see).
            int k = bins.index(std::min(c, 1.0), std::atan2(dot(dir, b), dot(dir, t)));
            ASSERT_GE(k, 0);
            observed[k] += 1;
            ASSERT_NEAR(length(dir), 1.0, 1e-6);
            (void)side_n;
        }
        if (h.two_sided) {
            double p = double(back) / ids.size();
            EXPECT_NEAR(p, 0.5, 5 * std::sqrt(0.25 / ids.size())) << name(h) << ": share emitted from the back";
        } else {
            EXPECT_EQ(back, 0u) << name(h) << ": a single-sided emitter emitted from its back";
        }
        Chi2Result c =
            chi2_test(observed, bins.expected([](double ct, double) { return ct / M_PI; }, double(ids.size())));
        EXPECT_TRUE(c.error.empty()) << name(h) << ": " << c.error;
        EXPECT_GT(c.p_value, kAlpha) << name(h) << ": chi2 " << c.chi2 << " dof " << c.dof;
    }
}

// The point light emits uniformly over the sphere (chi-square, 10 x 16 bins in (cos theta, phi)).
TEST(LightEmission, PointLightIsIsotropic) {
    Fixture& f = fixture();
    for (const HostLight& h : f.lights) {
        if (h.kind != Kind::Point) continue;
        std::vector<size_t> ids = f.photons_of(h.index);
        SphereBins bins{10, 16, -1, 1};
        std::vector<double> observed(bins.size(), 0);
        for (size_t id : ids) {
            D3 d = d3(&f.photons[9 * id + 3]);
            observed[bins.index(std::clamp(d.z, -1.0, 1.0), std::atan2(d.y, d.x))] += 1;
        }
        Chi2Result c =
            chi2_test(observed, bins.expected([](double, double) { return 1 / (4 * M_PI); }, double(ids.size())));
        EXPECT_GT(c.p_value, kAlpha) << "chi2 " << c.chi2 << " dof " << c.dof;
    }
}

// Spot photons stay inside the outer cone, are uniform in it (chi-square in cos theta), and their
// flux follows glTF's falloff: per bin of cos theta, the emitted power (sum of flux * P / N)
// equals 2 pi I int_bin falloff(c) dc, within 5 standard errors.
TEST(LightEmission, SpotEmitsInsideTheOuterConeWithGltfFalloff) {
    Fixture& f = fixture();
    const double ci = std::cos(double(kSpotInner)), co = std::cos(double(kSpotOuter));
    const double P = f.ds.info.total_power, N = double(Fixture::kPhotons);
    for (const HostLight& h : f.lights) {
        if (h.kind != Kind::Spot) continue;
        std::vector<size_t> ids = f.photons_of(h.index);
        const int nb = 12;
        std::vector<double> observed(nb, 0), expected(nb, 0);
        std::vector<double> sum(nb, 0), sum_sq(nb, 0);
        double min_cos = 1;
        const double lo = double(f.ds.lights[h.index].cos_outer);
        for (size_t id : ids) {
            double c = dot(d3(&f.photons[9 * id + 3]), h.direction);
            min_cos = std::min(min_cos, c);
            int k = std::clamp(int((c - lo) / (1 - lo) * nb), 0, nb - 1);
            observed[k] += 1;
            double x = f.photons[9 * id + 6] * P;
            sum[k] += x, sum_sq[k] += x * x;
        }
        EXPECT_GE(min_cos, lo - 1e-6) << "a photon outside the outer cone";
        for (int k = 0; k < nb; ++k) expected[k] = ids.size() / double(nb);
        Chi2Result c = chi2_test(observed, expected);
        EXPECT_GT(c.p_value, kAlpha) << "chi2 " << c.chi2 << " dof " << c.dof;
        for (int k = 0; k < nb; ++k) {
            double c0 = lo + (1 - lo) * k / nb, c1 = lo + (1 - lo) * (k + 1) / nb;
            double want = 0; // 2 pi I int falloff, by 64-point midpoint (the integrand is smooth)
            for (int s = 0; s < 64; ++s) want += spot_falloff(c0 + (c1 - c0) * (s + 0.5) / 64, ci, co) * (c1 - c0) / 64;
            want *= 2 * M_PI * h.rgb.x;
            MeanSe m = mean_se(sum[k], sum_sq[k], N);
            EXPECT_NEAR(m.mean, want, 5 * m.se + 1e-4 * want) << "cos bin " << k << " [" << c0 << ", " << c1 << ")";
        }
    }
}

// Directional photons all travel along the light's direction from a disc of radius R (the scene's
// bounding sphere) centred 1.01 R behind the scene's centre, perpendicular to the direction, and
// uniform over it: r^2 / R^2 uniform (10 bins) and phi uniform (16 bins), chi-square.
TEST(LightEmission, DirectionalPhotonsCoverTheSceneDiscUniformly) {
    Fixture& f = fixture();
    const D3 center = d3(f.ds.info.center);
    const double R = f.ds.info.radius;
    for (const HostLight& h : f.lights) {
        if (h.kind != Kind::Directional) continue;
        std::vector<size_t> ids = f.photons_of(h.index);
        D3 t, b;
        host_frame(h.direction, t, b);
        const D3 disc = center - (1.01 * R) * h.direction;
        std::vector<double> radial(10, 0), angular(16, 0);
        for (size_t id : ids) {
            D3 q = d3(&f.photons[9 * id]) - disc;
            ASSERT_LT(std::fabs(dot(q, h.direction)), 1e-5 * R) << "origin off the disc's plane";
            double x = dot(q, t), y = dot(q, b), r2 = (x * x + y * y) / (R * R);
            ASSERT_LE(r2, 1 + 1e-5);
            radial[std::min(9, int(r2 * 10))] += 1;
            double phi = std::atan2(y, x) + M_PI;
            angular[std::min(15, int(phi / (2 * M_PI) * 16))] += 1;
        }
        Chi2Result cr = chi2_test(radial, std::vector<double>(10, ids.size() / 10.0));
        Chi2Result ca = chi2_test(angular, std::vector<double>(16, ids.size() / 16.0));
        EXPECT_GT(cr.p_value, kAlpha) << "radial: chi2 " << cr.chi2;
        EXPECT_GT(ca.p_value, kAlpha) << "angular: chi2 " << ca.chi2;
    }
}

// sample_light's estimate of the irradiance at a point (the mean of contrib * cos over 4M
// samples, occlusion not tested) equals the sum over lights of the exact irradiance: Lambert's
// polygon formula for each triangle seen from its emitting side(s), I cos / d^2 for the point
// light, I falloff cos / d^2 for the spot, E cos for the sun. Run on the full scene and on its
// area lights alone (where triangle sampling is all there is: a 1% bias in it fails). Tolerance:
// 5 standard errors of the estimate plus 1e-4 relative.
TEST(LightEmission, SampleLightEstimatesIrradiance) {
    Fixture& f = fixture();
    struct Probe {
        D3 x, n;
    };
    const std::vector<Probe> probes = {
        {{0, -1, 0}, {0, 1, 0}},                           // the floor below everything
        {{0.2, 0.1, -0.3}, normalized({0.2, 1, -0.4})},    // sees A from below, C partly clipped
        {{1.2, 0.1, 1.5}, normalized({0, 0.2, -1})},       // in front of B's back face
        {{-1.2, 1.3, -1.2}, {0, -1, 0}},                   // facing A's back: no light from A
        {{-1.2, 0.8, -1.2}, normalized({0.1, 1, 0})},      // just below A, facing it
        {{0.6, 0.25, -0.9}, normalized({-0.3, 0.5, -1})}}; // close to C, grazing
    Scene area_scene = emission_scene();
    area_scene.punctual_lights.clear();
    DeviceScene area = upload_scene(f.dc, area_scene, RenderSettings{});
    std::vector<HostLight> area_lights = describe_lights(area_scene, area);
    const size_t items = 250000; // x 16 samples
    for (int which = 0; which < 2; ++which) {
        const DeviceScene& on = which == 0 ? f.ds : area;
        const std::vector<HostLight>& lights = which == 0 ? f.lights : area_lights;
        for (const Probe& pr : probes) {
            double min_dist = 0;
            std::vector<MeanSe> got = f.sample_light(on, pr.x, pr.n, items, &min_dist);
            D3 want{0, 0, 0};
            for (const HostLight& h : lights) {
                D3 e{0, 0, 0};
                if (h.kind == Kind::Triangle) {
                    double side = dot(pr.x - h.v0, h.n);
                    if (side > 0 || h.two_sided)
                        e = polygon_irradiance(pr.x, pr.n, {h.v0, h.v0 + h.e1, h.v0 + h.e2}, 1.0) * h.rgb;
                } else if (h.kind == Kind::Directional) {
                    e = std::max(0.0, -dot(pr.n, h.direction)) * h.rgb;
                } else {
                    D3 d = h.position - pr.x;
                    double d2 = dot(d, d), c = std::max(0.0, dot(pr.n, d) / std::sqrt(d2));
                    double fall = h.kind == Kind::Spot
                                      ? spot_falloff(-dot(normalized(d), h.direction), std::cos(double(kSpotInner)),
                                                     std::cos(double(kSpotOuter)))
                                      : 1.0;
                    e = (fall * c / d2) * h.rgb;
                }
                want = want + e;
            }
            for (int c = 0; c < 3; ++c) {
                double w = c == 0 ? want.x : c == 1 ? want.y : want.z;
                EXPECT_NEAR(got[c].mean, w, 5 * got[c].se + 1e-4 * w)
                    << (which == 0 ? "all lights" : "area lights only") << ", probe (" << pr.x.x << ", " << pr.x.y
                    << ", " << pr.x.z << ") channel " << c;
            }
            EXPECT_GT(min_dist, 0.0) << "a shadow ray of non-positive length was returned as valid";
        }
    }
}

// pick_light_reuse (the path tracer's light samples from one 2-D point) against a host reference:
// the light whose range of the CDF holds share * u.x, u.x rescaled to [0, 1) within that range,
// u.y untouched; with share < 1 (a uniform world left to the BSDF) only the lights below it. Given
// the light, the rescaled u.x is uniform (chi-square over 16 bins per light), so each light's
// point is as uniform as with a number of its own.
TEST(LightEmission, OnePointPicksTheLightAndPlacesIt) {
    Fixture& f = fixture();
    const size_t n = 200000;
    std::vector<float> u(3 * n);
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    for (float& x : u) x = std::min(uni(rng), 0.99999994f);
    const std::vector<float>& cdf = f.ds.light_cdf;
    const size_t lights = f.ds.lights.size();
    for (const float share : {1.0f, cdf[lights - 2]}) {
        cl::Buffer ub(f.dc.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, u.size() * sizeof(float), u.data());
        cl::Buffer out(f.dc.context, CL_MEM_WRITE_ONLY, 3 * n * sizeof(float));
        cl::Kernel k(f.program, "pick_reuse_many");
        int a = f.ds.set_scene_args(k);
        k.setArg(a++, share), k.setArg(a++, ub), k.setArg(a++, out);
        f.dc.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(n));
        const std::vector<float> got = f.read<float>(out, 3 * n);
        std::vector<std::vector<double>> bins(lights, std::vector<double>(16, 0));
        int wrong_light = 0;
        double worst = 0;
        for (size_t i = 0; i < n; ++i) {
            const double v = double(u[3 * i]) * share;
            size_t l = 0;
            while (l + 1 < lights && double(cdf[l + 1]) <= v) ++l;
            const size_t dl = size_t(got[3 * i]);
            ASSERT_LT(dl, lights);
            EXPECT_LT(double(cdf[dl]), share) << "a light above the share was picked";
            if (dl != l) { // v on a range's edge, rounded the other way
                ++wrong_light;
                continue;
            }
            const double w = double(cdf[l + 1]) - double(cdf[l]);
            const double want = w >= share / 4096.0 ? (v - double(cdf[l])) / w : double(u[3 * i + 2]);
            worst = std::max(worst, std::fabs(got[3 * i + 1] - want));
            EXPECT_EQ(got[3 * i + 2], u[3 * i + 1]);
            bins[l][std::min(15, int(got[3 * i + 1] * 16))] += 1;
        }
        EXPECT_LE(wrong_light, 2) << "share " << share;
        EXPECT_LT(worst, 2e-4) << "share " << share; // float v - cdf over a range of width w >= 1/4096
        for (size_t l = 0; l < lights; ++l) {
            const double total = std::accumulate(bins[l].begin(), bins[l].end(), 0.0);
            if (double(cdf[l]) >= share) {
                EXPECT_EQ(total, 0) << "light " << l << " lies above share " << share;
                continue;
            }
            if (total < 16 * 20) continue;
            const Chi2Result r = chi2_test(bins[l], std::vector<double>(16, total / 16));
            EXPECT_GT(r.p_value, 1e-4) << "light " << l << ", share " << share << ": chi2 " << r.chi2;
        }
    }
}

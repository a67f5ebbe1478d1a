// Textures on the device against the host reference (src/scene/texture_sampling.cpp), and
// emissive textures end to end: an emitter's power is its texture's integral, photons leave it
// where the texture is bright and carry the texture's value, and a render with a half-black
// emissive texture equals the render of the same scene with only that half emitting, for photon
// mapping and the path tracer (whose MIS finds the textured triangle's light by binary search).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "device/kernel_program.h"
#include "io/image_io.h"
#include "photon_emission.h"
#include "scene/device_scene.h"
#include "scene/gltf/gltf_load.h"
#include "scene/light_power.h"
#include "scene/texture_sampling.h"
#include "scene_builders.h"
#include "stat_tests.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

std::string data(const char* name) { return std::string(CLPPM_TEST_DATA) + "/" + name; }

const char* kWrappers = R"CL(
__kernel void lookup_many(SCENE_PARAMS, int tex, __global const float* uv, __global float* out) {
    uint i = get_global_id(0);
    float3 c = texture_lookup(SCENE_ARGS, tex, (float4)(uv[4 * i], uv[4 * i + 1], uv[4 * i + 2], uv[4 * i + 3]));
    out[3 * i] = c.x; out[3 * i + 1] = c.y; out[3 * i + 2] = c.z;
}
)CL";

cl::Program build(const DeviceContext& dc) {
    return build_test_program(dc, assemble_kernel_source("rng.cl") + assemble_kernel_source("lights.cl") +
                                      kEmitManyKernel + kWrappers);
}

} // namespace

// Bilinear weights, texel centres, REPEAT, MIRRORED_REPEAT and CLAMP_TO_EDGE on each axis, each
// also with magFilter NEAREST, a KHR_texture_transform on TEXCOORD_1, coordinates far outside
// [0, 1] and non-finite ones: the device's texture_lookup against the host's. A NEAREST lookup
// is one of its texels exactly.
TEST(TextureSampling, DeviceLookupMatchesTheHostReference) {
    Scene s;
    s.source = "<texture test>";
    add_quad(s, {-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, add_material(s, 0.5f, 0.5f, 0.5f, 1.f));
    std::mt19937 gen(7);
    std::uniform_real_distribution<float> texel(0.f, 1.f);
    // Every combination of REPEAT, MIRRORED_REPEAT and CLAMP_TO_EDGE per axis, then a transformed
    // reference on the second coordinate set.
    const uint32_t modes[3] = {0, TEXTURE_CLAMP_S, TEXTURE_MIRROR_S};
    for (uint32_t filter : {0u, TEXTURE_NEAREST})
        for (uint32_t ms : modes)
            for (uint32_t mt : modes) {
                const uint32_t w = 3 + uint32_t(s.textures.size() % 3), h = 2 + uint32_t(s.textures.size() % 2);
                s.textures.push_back(plain_texture(uint32_t(s.texels.size()), w, h, ms | (mt << 1) | filter));
                for (uint32_t i = 0; i < w * h; ++i) s.texels.push_back({texel(gen), texel(gen), texel(gen), 1.f});
            }
    dev::Texture moved = s.textures[4];
    const float xform[6] = {0.7f, 0.5f, 0.25f, -0.5f, 0.7f, 1.f};
    std::copy(xform, xform + 6, moved.xform);
    moved.texcoord = 1;
    s.textures.push_back(moved);
    std::vector<float> uv; // (TEXCOORD_0, TEXCOORD_1) per lookup
    std::uniform_real_distribution<float> coord(-3.f, 3.f);
    for (int i = 0; i < 8000; ++i) uv.push_back(coord(gen));
    for (float u : {0.f, 1.f, 0.5f, 1e9f, -1e9f, 3e38f, -3e38f, INFINITY, NAN})
        uv.insert(uv.end(), {u, 0.25f, 0.25f, u});
    const size_t n = uv.size() / 4;
    DeviceContext dc(test_device());
    DeviceScene ds = upload_scene(dc, s, RenderSettings{});
    cl::Program program = build(dc);
    cl::Buffer in(dc.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, uv.size() * sizeof(float), uv.data());
    cl::Buffer out(dc.context, CL_MEM_WRITE_ONLY, 3 * n * sizeof(float));
    for (int tex = 0; tex < int(s.textures.size()); ++tex) {
        SCOPED_TRACE("texture " + std::to_string(tex));
        cl::Kernel k(program, "lookup_many");
        int a = ds.set_scene_args(k);
        k.setArg(a++, cl_int(tex)), k.setArg(a++, in), k.setArg(a++, out);
        dc.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(n));
        std::vector<float> got = read_buffer<float>(dc, out, 3 * n);
        const dev::Texture& t = s.textures[size_t(tex)];
        const bool nearest = (t.wrap & TEXTURE_NEAREST) != 0;
        double worst = 0;
        size_t not_a_texel = 0;
        for (size_t i = 0; i < n; ++i) {
            const size_t set = t.texcoord ? 2 : 0;
            std::array<double, 3> want = sample_texture(s, tex, uv[4 * i + set], uv[4 * i + set + 1]);
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(got[3 * i + size_t(c)] - want[size_t(c)]));
            bool is_texel = false;
            for (uint32_t j = t.offset; j < t.offset + t.width * t.height; ++j)
                is_texel |= got[3 * i] == s.texels[j][0] && got[3 * i + 1] == s.texels[j][1] &&
                            got[3 * i + 2] == s.texels[j][2];
            not_a_texel += !is_texel;
        }
        // Float coordinates against double: a texel's weight moves by ~|u| w 2^-24.
        EXPECT_LT(worst, 2e-5);
        if (nearest) EXPECT_EQ(not_a_texel, 0u);
        else EXPECT_GT(not_a_texel, n / 2); // bilinear blends
    }
}

// Clamped 64x1 texture, white for u < 0.5: the triangle v <= u of the unit uv square has mean
// 2 int_0^1 f(u) u du = 1/4 (the bilinear ramp's correction is h^2 / 6, h = 1/128), the other
// 3/4; the emission factor is 4.
TEST(EmissiveTexture, EmitterPowerIsTheIntegralOfItsTexture) {
    Scene s = load_gltf(data("emissive_texture.gltf"));
    ASSERT_TRUE(s.warnings.empty()) << s.warnings[0];
    std::vector<double> means;
    for (size_t t = 0; t < s.num_triangles(); ++t)
        if (s.materials[s.shading[t].material].emissive_tex >= 0) means.push_back(textured_emission_mean(s, t));
    ASSERT_EQ(means.size(), 2u);
    EXPECT_NEAR(means[0], 4 * 0.25, 4e-3);
    EXPECT_NEAR(means[1], 4 * 0.75, 4e-3);
    DeviceContext dc(test_device());
    DeviceScene ds = upload_scene(dc, s, RenderSettings{});
    EXPECT_NEAR(ds.info.total_power, 4 * 0.5 * M_PI, 4 * 0.5 * M_PI * 1e-3) << "int Le pi dA over the unit square";
}

// Photons leave the emitter only where its texture is bright (none from u > 0.5 + 1/128, past
// the bilinear ramp) and carry Le(x) A pi / (pick P): their flux averages to the true power over
// P, whatever the power the light choice used.
TEST(EmissiveTexture, PhotonsLeaveWhereTheTextureIsBrightWithUnbiasedFlux) {
    Scene s = load_gltf(data("emissive_texture.gltf"));
    DeviceContext dc(test_device());
    DeviceScene ds = upload_scene(dc, s, RenderSettings{});
    cl::Program program = build(dc);
    const size_t n = 400000;
    const std::vector<float> p = emit_photons(dc, ds, program, 3, n);
    double sum = 0, sum_sq = 0, dark = 0, ramp = 0;
    for (size_t i = 0; i < n; ++i) {
        const float* o = &p[kEmittedFloats * i];
        const double flux = (double(o[6]) + o[7] + o[8]) / 3, u = o[0] + 0.5;
        sum += flux, sum_sq += flux * flux;
        if (u > 0.5 + 1.0 / 128) dark += flux;
        else if (u > 0.5 - 1.0 / 128) ramp += flux;
    }
    MeanSe m = mean_se(sum, sum_sq, double(n));
    // The true power over the chosen power: 1 up to the power integral's quadrature error.
    const double expected = 4 * 0.5 * M_PI / ds.info.total_power;
    EXPECT_NEAR(m.mean, expected, 5 * m.se + 1e-3) << "se " << m.se;
    EXPECT_EQ(dark, 0.0) << "no flux from black texels";
    // The ramp is 1/64 of the square wide at half intensity on average, and the lit half emits
    // at intensity 1: 1/128 of 1/2, 1/64 of the power.
    EXPECT_NEAR(ramp / sum, 1.0 / 64, 2e-3);
}

// End to end: the textured lamp renders like the half lamp, for photon mapping and path
// tracing, and unlike a lamp whose texture is ignored (twice the light).
TEST(EmissiveTexture, RendersLikeTheEmitterItsTextureDescribes) {
    for (const char* integrator : {"sppm", "pt"}) {
        SCOPED_TRACE(integrator);
        const double mean[2] = {render_test_scene_mean("emissive_texture.gltf", integrator, 8, 60000),
                                render_test_scene_mean("emissive_split.gltf", integrator, 8, 60000)};
        ASSERT_GT(mean[1], 0);
        // Measured: 1.005 (SPPM) and 1.010 (PT) at 6 passes, differences of noise.
        EXPECT_NEAR(mean[0] / mean[1], 1.0, 0.03);
    }
}

// The device compiler must lay out every shared struct exactly as the host does: sizes and field
// offsets measured by a kernel on the test device, compared with the host's sizeof/offsetof.
#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <vector>

#include "device/kernel_program.h"
#include "shared_types.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::dev;

namespace {

// One struct per line, as written:
// clang-format off
#define LAYOUT_FIELDS(X)                                                                            \
    X(sizeof(TriShading)) X(offsetof(TriShading, uv0)) X(offsetof(TriShading, material))            \
    X(sizeof(BvhNode)) X(offsetof(BvhNode, bmax_x)) X(offsetof(BvhNode, child)) X(offsetof(BvhNode, count)) \
    X(sizeof(BvhTriBlock)) X(offsetof(BvhTriBlock, prim))                                            \
    X(sizeof(Material)) X(offsetof(Material, emission)) X(offsetof(Material, outside)) X(offsetof(Material, metallic))                \
    X(offsetof(Material, base_color_tex)) X(offsetof(Material, specular_color)) X(offsetof(Material, normal_tex))                                 \
    X(sizeof(Texture)) X(offsetof(Texture, wrap)) X(offsetof(Texture, texcoord))                                                     \
    X(sizeof(Light)) X(offsetof(Light, power)) X(offsetof(Light, position)) X(offsetof(Light, radiance)) \
    X(offsetof(Light, cos_inner)) X(offsetof(Light, area))                                            \
    X(sizeof(Camera)) X(offsetof(Camera, width)) X(offsetof(Camera, focus_distance))                  \
    X(sizeof(SceneInfo)) X(offsetof(SceneInfo, radius)) X(offsetof(SceneInfo, total_power))           \
    X(offsetof(SceneInfo, max_bounces))                                                               \
    X(sizeof(HitPoint)) X(offsetof(HitPoint, weight)) X(offsetof(HitPoint, footprint)) X(offsetof(HitPoint, alpha)) \
    X(offsetof(HitPoint, normal_oct)) X(offsetof(HitPoint, wo_oct)) X(offsetof(HitPoint, f0)) X(offsetof(HitPoint, metal)) \
    X(offsetof(HitPoint, volume)) X(offsetof(HitPoint, volume_behind)) \
    X(sizeof(PassFlux)) X(offsetof(PassFlux, m))                                                      \
    X(sizeof(HitStats)) X(offsetof(HitStats, n)) X(offsetof(HitStats, tau)) X(offsetof(HitStats, direct)) \
    X(sizeof(Photon)) X(offsetof(Photon, flux)) X(offsetof(Photon, wi_oct))                           \
    X(sizeof(GridInfo)) X(offsetof(GridInfo, inv_cell)) X(offsetof(GridInfo, num_photons))            \
    X(sizeof(LightVertex)) X(offsetof(LightVertex, throughput)) X(offsetof(LightVertex, d_vm))         \
    X(offsetof(LightVertex, u)) X(offsetof(LightVertex, path_length))                              \
    X(sizeof(VcmPass)) X(offsetof(VcmPass, light_unit)) X(offsetof(VcmPass, light_paths))          \
    X(offsetof(VcmPass, r2)) X(offsetof(VcmPass, max_len))
// clang-format on

#define STR(x) #x ","
#define VAL(x) static_cast<unsigned>(x),

} // namespace

TEST(SharedTypes, DeviceLayoutMatchesHost) {
    const std::vector<unsigned> host = {LAYOUT_FIELDS(VAL)};
    std::string exprs = LAYOUT_FIELDS(STR);
    std::string body;
    size_t i = 0, start = 0;
    for (size_t p = 0; p < exprs.size(); ++p)
        if (exprs[p] == ',' && (p + 1 == exprs.size() || exprs[p + 1] == 's' || exprs[p + 1] == 'o')) {
            body += "    out[" + std::to_string(i++) + "] = (uint)(" + exprs.substr(start, p - start) + ");\n";
            start = p + 1;
        }
    ASSERT_EQ(i, host.size());
    std::string src = assemble_kernel_source("shared_types.h") +
                      "\n#define offsetof(T, f) ((size_t)&(((T*)0)->f))\n__kernel void layout(__global uint* out) {\n" +
                      body + "}\n";
    test::KernelHarness h(src);
    cl::Buffer out = h.output(host.size() * sizeof(cl_uint));
    cl::Kernel k(h.program, "layout");
    k.setArg(0, out);
    h.run(k, 1);
    const std::vector<cl_uint> device = h.read<cl_uint>(out, host.size());
    for (size_t k2 = 0; k2 < host.size(); ++k2) EXPECT_EQ(device[k2], host[k2]) << "layout entry " << k2;
}

// A struct passed by value (dev::VcmPass, vcm_light and vcm_camera) arrives as the host wrote it:
// every field read back from the kernel's argument.
TEST(SharedTypes, StructArgumentArrivesByValue) {
    const std::string src = assemble_kernel_source("shared_types.h") + R"(
__kernel void echo(const VcmPass vp, __global double* out) {
    out[0] = (double)vp.seed; out[1] = (double)vp.pass; out[2] = vp.light_unit; out[3] = vp.vm_norm;
    out[4] = vp.splat_unit; out[5] = vp.light_paths; out[6] = vp.vm_factor; out[7] = vp.vc_factor;
    out[8] = vp.area_scale; out[9] = vp.r2; out[10] = vp.splat_scale; out[11] = vp.mode; out[12] = vp.max_len;
}
)";
    test::KernelHarness h(src);
    VcmPass vp{};
    vp.seed = 123456789;
    vp.pass = 42;
    vp.light_unit = 1.5e-7;
    vp.vm_norm = 2.25;
    vp.splat_unit = 3.0e-9;
    vp.light_paths = 4096.f;
    vp.vm_factor = 0.5f;
    vp.vc_factor = 2.f;
    vp.area_scale = 0.125f;
    vp.r2 = 1e-4f;
    vp.splat_scale = 65536.f;
    vp.mode = 3;
    vp.max_len = 9;
    cl::Buffer out = h.output(13 * sizeof(cl_double));
    cl::Kernel k(h.program, "echo");
    k.setArg(0, vp);
    k.setArg(1, out);
    h.run(k, 1);
    const std::vector<cl_double> got = h.read<cl_double>(out, 13);
    const std::vector<double> want = {123456789.0, 42.0,  1.5e-7,        2.25,    3.0e-9, 4096.0, 0.5,
                                      2.0,         0.125, double(1e-4f), 65536.0, 3.0,    9.0};
    for (size_t i = 0; i < want.size(); ++i) EXPECT_EQ(got[i], want[i]) << "field " << i;
}

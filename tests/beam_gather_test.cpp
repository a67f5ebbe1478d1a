// The beam radiance estimate's gather (kernels/beam.cl beam_gather) against a brute-force sum over
// every photon, in double: each beam takes the photons stored in media whose distance along its
// ray falls within [0, t_max] and whose distance from the ray is below r, each once, weighted by
// the transmittance to it and the Henyey-Greenstein phase function, whatever the cell size, the
// table's crowding or where the beam starts and ends. The grid (beam_grid_count, beam_grid_scatter)
// holds the photons stored in media alone; slots that are not beams are left untouched.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "device/kernel_program.h"
#include "device_grid.h"
#include "octahedral.h"
#include "shared_types.h"
#include "test_util.h"

using namespace clppm;
using clppm::test::oct;
using clppm::test::unoct;

namespace {

struct BeamCase {
    std::vector<dev::Photon> photons;
    std::vector<dev::HitPoint> slots; // beams, and one surface hit point the beam gather leaves alone
    dev::GridInfo grid{};
    float r2 = 0;
};

// 60000 photons in the cube [-1, 1]^3, two in three stored in media (the world's, a few a mesh's);
// 200 beams from inside and outside the cube, 0.02 to 4 long, in chromatic media with g of either
// sign, a fifth in the mesh's medium, whose photons alone they gather.
BeamCase make_case(float cell, float radius, uint32_t table_size, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1), u01(0, 1);
    BeamCase c;
    for (uint32_t i = 0; i < 60000; ++i) {
        dev::Photon p{};
        for (int k = 0; k < 3; ++k) p.pos[k] = float(u(rng));
        const double wx = u(rng), wy = u(rng), wz = u(rng), l = std::sqrt(wx * wx + wy * wy + wz * wz);
        p.wi_oct = oct(wx / l, wy / l, wz / l);
        p.normal_oct = oct(0, 1, 0);
        for (int k = 0; k < 3; ++k) p.flux[k] = float(0.1 + 2 * u01(rng));
        if (i % 3 != 0) {
            uint32_t bits;
            std::memcpy(&bits, &p.flux[1], sizeof bits);
            bits |= PHOTON_VOLUME_FLAG;
            std::memcpy(&p.flux[1], &bits, sizeof bits);
            p.normal_oct = i % 7 == 1 ? 2 : 0; // its medium (kernels/medium.cl Medium.id)
        }
        c.photons.push_back(p);
    }
    const float gs[3] = {0.f, 0.7f, -0.4f};
    for (uint32_t i = 0; i < 200; ++i) {
        dev::HitPoint h{};
        for (int k = 0; k < 3; ++k) h.pos[k] = float(1.4 * u(rng));
        const double dx = u(rng), dy = u(rng), dz = u(rng), l = std::sqrt(dx * dx + dy * dy + dz * dz);
        h.f0[0] = float(dx / l), h.f0[1] = float(dy / l), h.f0[2] = float(dz / l);
        h.wo_oct = oct(-dx / l, -dy / l, -dz / l);
        h.dielectric = float(0.02 + 4 * u01(rng) * u01(rng));
        for (int k = 0; k < 3; ++k) h.color[k] = float(k == 2 && i % 4 == 0 ? 0 : 0.2 + 2 * u01(rng)), h.weight[k] = 1;
        h.alpha = HITPOINT_BEAM_ALPHA;
        h.f90 = gs[i % 3];
        h.t_oct = i % 5 == 0 ? 2 : 0; // its medium
        h.pixel = i;
        c.slots.push_back(h);
    }
    dev::HitPoint surface{}; // a hit point on a surface: gather's, which beam_gather must not touch
    surface.pixel = 7;
    c.slots.push_back(surface);
    c.grid.origin[0] = c.grid.origin[1] = c.grid.origin[2] = -1.25f;
    c.grid.inv_cell = 1.0f / cell;
    c.grid.table_size = table_size;
    c.grid.num_photons = uint32_t(c.photons.size());
    c.r2 = radius * radius;
    return c;
}

std::vector<dev::PassFlux> device_beam_gather(const BeamCase& c, const dev::PassFlux& sentinel) {
    DeviceContext dc(test::test_device());
    cl::Program program(dc.context, assemble_kernel_source("beam.cl"));
    program.build({dc.info.device}, "-cl-std=CL1.2");
    const cl::Context& ctx = dc.context;
    const test::DeviceGrid grid = test::build_device_grid(dc, program, c.grid, c.photons, "beam_");
    cl::Buffer slots = test::copy_buffer(ctx, c.slots.data(), c.slots.size() * sizeof(dev::HitPoint));
    std::vector<dev::PassFlux> result(c.slots.size(), sentinel);
    cl::Buffer out = test::copy_buffer(ctx, result.data(), result.size() * sizeof(dev::PassFlux));
    cl::Kernel gather(program, "beam_gather");
    gather.setArg(0, grid.info), gather.setArg(1, grid.sorted), gather.setArg(2, grid.starts), gather.setArg(3, slots);
    gather.setArg(4, cl_uint(c.slots.size())), gather.setArg(5, cl_float(c.r2)), gather.setArg(6, cl_uint(0));
    gather.setArg(7, out), gather.setArg(8, cl_ulong(1)), gather.setArg(9, cl_ulong(1));
    dc.queue.enqueueNDRangeKernel(gather, cl::NullRange, cl::NDRange(c.slots.size()));
    dc.queue.enqueueReadBuffer(out, CL_TRUE, 0, result.size() * sizeof(dev::PassFlux), result.data());
    return result;
}

// The sum for beam h in double. A photon within 1e-5 of the segment's ends or of the cylinder's
// surface may fall either way in float: those are counted apart (*m_edge, flux_edge).
void brute_force(const BeamCase& c, const dev::HitPoint& h, uint32_t* m, uint32_t* m_edge, double want[3],
                 double edge[3]) {
    const double o[3] = {h.pos[0], h.pos[1], h.pos[2]}, d[3] = {h.f0[0], h.f0[1], h.f0[2]};
    const double t_max = h.dielectric, r2 = c.r2, g = h.f90;
    *m = *m_edge = 0;
    for (int k = 0; k < 3; ++k) want[k] = edge[k] = 0;
    for (const dev::Photon& p : c.photons) {
        uint32_t bits;
        std::memcpy(&bits, &p.flux[1], sizeof bits);
        if (!(bits & PHOTON_VOLUME_FLAG) || p.normal_oct != h.t_oct) continue; // another medium's stay there
        const double v[3] = {p.pos[0] - o[0], p.pos[1] - o[1], p.pos[2] - o[2]};
        const double tp = v[0] * d[0] + v[1] * d[1] + v[2] * d[2];
        const double e[3] = {v[0] - tp * d[0], v[1] - tp * d[1], v[2] - tp * d[2]};
        const double d2 = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
        const double eps = 1e-5;
        const bool near_edge = std::fabs(tp) < eps || std::fabs(tp - t_max) < eps || std::fabs(d2 - r2) < eps * r2;
        if (!near_edge && (tp < 0 || tp > t_max || d2 > r2)) continue;
        double wi[3];
        unoct(p.wi_oct, wi);
        const double cos_t = wi[0] * d[0] + wi[1] * d[1] + wi[2] * d[2];
        const double q = 1 + g * g - 2 * g * cos_t, phase = (1 - g * g) / (4 * M_PI * q * std::sqrt(q));
        const double flux[3] = {p.flux[0], -double(p.flux[1]), p.flux[2]};
        for (int k = 0; k < 3; ++k) {
            const double T = h.color[k] > 0 ? std::exp(-double(h.color[k]) * tp) : 1.0;
            (near_edge ? edge : want)[k] += flux[k] * T * phase;
        }
        ++*(near_edge ? m_edge : m);
    }
}

void expect_matches(const BeamCase& c, const char* what) {
    const dev::PassFlux sentinel{{11, 22, 33}, 44, 0};
    const std::vector<dev::PassFlux> got = device_beam_gather(c, sentinel);
    uint64_t total = 0;
    for (size_t i = 0; i + 1 < c.slots.size(); ++i) {
        uint32_t m, m_edge;
        double want[3], edge[3];
        brute_force(c, c.slots[i], &m, &m_edge, want, edge);
        total += m;
        ASSERT_GE(got[i].m, m) << what << ", beam " << i;
        ASSERT_LE(got[i].m, m + m_edge) << what << ", beam " << i;
        for (int k = 0; k < 3; ++k)
            ASSERT_NEAR(double(got[i].flux[k]) / FLUX_FIXED_SCALE, want[k] + 0.5 * edge[k],
                        1e-5 * want[k] + 0.5 * edge[k] + 1e-6)
                << what << ", beam " << i << ", channel " << k;
    }
    const dev::PassFlux& s = got.back();
    EXPECT_TRUE(s.m == sentinel.m && s.flux[0] == 11 && s.flux[1] == 22 && s.flux[2] == 33)
        << what << ": a slot that is not a beam was written";
    EXPECT_GT(total, 200u) << what << ": the beams must actually gather";
}

} // namespace

TEST(BeamGather, MatchesBruteForceWithCellsOfTwiceTheRadius) {
    expect_matches(make_case(0.1f, 0.05f, 65536, 1), "cell 2r");
}

TEST(BeamGather, MatchesBruteForceForRadiiAroundTheCellSize) {
    expect_matches(make_case(0.1f, 0.02f, 65536, 2), "cell 5r");
    expect_matches(make_case(0.05f, 0.1f, 65536, 3), "cell r/2");
}

TEST(BeamGather, CrowdedHashTableStillCountsEachPhotonOnce) {
    expect_matches(make_case(0.04f, 0.04f, 1024, 4), "crowded table");
}

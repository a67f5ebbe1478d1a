// The hashed-grid gather (kernels/hash_grid.cl, kernels/gather.cl) against a brute-force gather
// over all photons: the same photons counted, the same flux sums to the last fixed-point unit,
// for radii smaller than, equal to and larger than a cell, and hit points on cell boundaries; each
// hit point's sum divided by its disc's covered fraction (kernels/disc_coverage.cl). Volume hit
// points (participating media) take the photons stored in media within their sphere, weighted by
// the phase function over sigma_t, and surfaces never take those.
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

struct GatherCase {
    std::vector<dev::Photon> photons;
    std::vector<dev::HitPoint> hitpoints;
    std::vector<dev::HitStats> stats;
    std::vector<cl_float2> coverage; // (f, g) per hit point; the gather divides by f
    dev::GridInfo grid{};
    float volume_r2 = 0;
};

// Photons and hit points on the plane y = 0 (normal +y) and on its underside; some photons
// arrive from below (rejected by direction), some lie on the downward face (rejected by normal).
GatherCase make_case(float cell, float radius, uint32_t n_photons, uint32_t n_hit, bool on_boundaries, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.f, 1.f), u01(0.f, 1.f);
    GatherCase c;
    for (uint32_t i = 0; i < n_photons; ++i) {
        dev::Photon p{};
        p.pos[0] = u(rng), p.pos[1] = 0.002f * u(rng), p.pos[2] = u(rng);
        bool down = u01(rng) < 0.2f, from_below = u01(rng) < 0.2f;
        p.normal_oct = oct(0, down ? -1.f : 1.f, 0);
        float wx = u(rng) * 0.5f, wz = u(rng) * 0.5f, wy = (from_below ? -1.f : 1.f) * (0.3f + u01(rng));
        float l = std::sqrt(wx * wx + wy * wy + wz * wz);
        p.wi_oct = oct(wx / l, wy / l, wz / l);
        for (int k = 0; k < 3; ++k) p.flux[k] = 0.1f + 2.f * u01(rng);
        c.photons.push_back(p);
    }
    for (uint32_t i = 0; i < n_hit; ++i) {
        dev::HitPoint h{};
        float x = u(rng) * 0.9f, z = u(rng) * 0.9f;
        if (on_boundaries) { // exactly on cell faces of the grid (origin -1.25)
            x = -1.25f + cell * std::round((x + 1.25f) / cell);
            if (i % 2) z = -1.25f + cell * std::round((z + 1.25f) / cell);
        }
        h.pos[0] = x, h.pos[1] = 0, h.pos[2] = z;
        h.normal_oct = oct(0, 1, 0);
        h.wo_oct = h.normal_oct;
        h.nl_oct = h.normal_oct;                  // no normal map: the smooth normal is the shading normal
        h.color[0] = h.color[1] = h.color[2] = 1; // Lambertian (no layer: f0 = f90 = 0), f = 1/pi
        h.alpha = 1;
        h.dielectric = 1;
        h.weight[0] = h.weight[1] = h.weight[2] = 1;
        h.pixel = i;
        c.hitpoints.push_back(h);
        float r = radius * (0.5f + u01(rng)); // radii vary around the nominal one
        c.stats.push_back(dev::HitStats{double(r) * r, 0, {0, 0, 0}, {0, 0, 0}});
        c.coverage.push_back(cl_float2{{i % 3 == 0 ? 1.0f : 0.125f + 0.875f * u01(rng), 1.0f}});
    }
    c.grid.origin[0] = c.grid.origin[1] = c.grid.origin[2] = -1.25f;
    c.grid.inv_cell = 1.f / cell;
    c.grid.num_photons = n_photons;
    c.grid.table_size = 1024;
    while (c.grid.table_size < n_photons) c.grid.table_size <<= 1;
    return c;
}

bool photon_in_volume(const dev::Photon& p) {
    uint32_t bits;
    std::memcpy(&bits, &p.flux[1], sizeof bits);
    return (bits & PHOTON_VOLUME_FLAG) != 0;
}

// Brute force: every photon against every hit point, the rules written out plainly.
std::vector<dev::PassFlux> brute_force(const GatherCase& c) {
    std::vector<dev::PassFlux> out(c.hitpoints.size());
    for (size_t i = 0; i < c.hitpoints.size(); ++i) {
        const dev::HitPoint& h = c.hitpoints[i];
        float r2 = float(c.stats[i].r2);
        for (const dev::Photon& p : c.photons) {
            float dx = p.pos[0] - h.pos[0], dy = p.pos[1] - h.pos[1], dz = p.pos[2] - h.pos[2];
            if (dx * dx + dy * dy + dz * dz > r2) continue;
            // Accepted photons arrive from above (wi.y > 0) on an upward face (normal.y > 0): the
            // encodings put y in the upper 16 bits, above the midpoint for positive y.
            bool wi_up = (p.wi_oct >> 16) > 32768, n_up = (p.normal_oct >> 16) > 32768;
            if (!wi_up || !n_up || photon_in_volume(p)) continue;
            const float f = 1.0f * 0.31830988618379067154f; // albedo 1 / pi, in float as the kernel
            const float inv_cover = 1.0f / c.coverage[i].s[0];
            for (int k = 0; k < 3; ++k)
                out[i].flux[k] += std::llrint(double(f * (p.flux[k] * inv_cover)) * FLUX_FIXED_SCALE);
            out[i].m += 1;
        }
    }
    return out;
}

std::vector<dev::PassFlux> device_gather(const GatherCase& c) {
    DeviceContext dc(test::test_device());
    cl::Program program(dc.context, assemble_kernel_source("gather.cl"));
    program.build({dc.info.device}, "-cl-std=CL1.2");
    const cl::Context& ctx = dc.context;
    const test::DeviceGrid grid = test::build_device_grid(dc, program, c.grid, c.photons);
    cl::Buffer hps = test::copy_buffer(ctx, c.hitpoints.data(), c.hitpoints.size() * sizeof(dev::HitPoint));
    cl::Buffer stats = test::copy_buffer(ctx, c.stats.data(), c.stats.size() * sizeof(dev::HitStats));
    cl::Buffer out(ctx, CL_MEM_READ_WRITE, c.hitpoints.size() * sizeof(dev::PassFlux));
    cl::Buffer coverage = test::copy_buffer(ctx, c.coverage.data(), c.coverage.size() * sizeof(cl_float2));
    cl::Kernel gather(program, "gather");
    gather.setArg(0, grid.info), gather.setArg(1, grid.sorted), gather.setArg(2, grid.starts), gather.setArg(3, hps);
    gather.setArg(4, stats), gather.setArg(5, cl_uint(c.hitpoints.size())), gather.setArg(6, cl_float(0));
    gather.setArg(7, cl_float(c.volume_r2)), gather.setArg(8, cl_uint(0)), gather.setArg(9, out);
    gather.setArg(10, cl_ulong(1)), gather.setArg(11, cl_ulong(1)), gather.setArg(12, coverage);
    dc.queue.enqueueNDRangeKernel(gather, cl::NullRange, cl::NDRange(c.hitpoints.size()));
    std::vector<dev::PassFlux> result(c.hitpoints.size());
    dc.queue.enqueueReadBuffer(out, CL_TRUE, 0, result.size() * sizeof(dev::PassFlux), result.data());
    return result;
}

void expect_same(const GatherCase& c, const char* what) {
    std::vector<dev::PassFlux> got = device_gather(c), want = brute_force(c);
    uint64_t total = 0;
    for (size_t i = 0; i < want.size(); ++i) {
        total += want[i].m;
        ASSERT_EQ(got[i].m, want[i].m) << what << ", hit point " << i;
        for (int k = 0; k < 3; ++k) ASSERT_EQ(got[i].flux[k], want[i].flux[k]) << what << ", hit point " << i;
    }
    EXPECT_GT(total, want.size()) << what << ": the case must actually gather photons";
}

} // namespace

TEST(Gather, MatchesBruteForceForRadiiAroundTheCellSize) {
    const float cell = 0.05f;
    expect_same(make_case(cell, 0.3f * cell, 20000, 500, false, 1), "radius 0.3 cell");
    expect_same(make_case(cell, 0.5f * cell, 20000, 500, false, 2), "radius = half cell");
    expect_same(make_case(cell, 1.0f * cell, 20000, 500, false, 3), "radius = cell");
    expect_same(make_case(cell, 3.0f * cell, 20000, 500, false, 4), "radius 3 cells");
}

TEST(Gather, HitPointsOnCellBoundaries) {
    const float cell = 0.05f;
    expect_same(make_case(cell, 0.5f * cell, 20000, 500, true, 5), "boundaries, half cell");
    expect_same(make_case(cell, 2.0f * cell, 20000, 500, true, 6), "boundaries, two cells");
}

TEST(Gather, CrowdedHashTableStillCountsEachPhotonOnce) {
    // A tiny table (1024 buckets for 20k photons in thousands of cells) forces many cells into
    // each bucket: a photon must be counted only from its own cell.
    GatherCase c = make_case(0.02f, 0.05f, 20000, 300, false, 7);
    c.grid.table_size = 1024;
    expect_same(c, "crowded table");
}

// make_case's plane with as many photons again stored in media through the cube around it (half
// of them lying on the plane, arriving from above on an upward normal, as surface photons the
// plane's hit points would take), and volume hit points through the cube: the surface sums are
// still the plane's photons' to the last unit, and each volume hit point sums, over the volume
// photons of its own medium (the world's, or a fifth of them a mesh's) within its sphere, flux / sigma_t times the Henyey-Greenstein phase function of the
// angle between the photon's direction and the way to the eye (relative 1e-5 of the sum: the
// kernel's float against double here).
TEST(Gather, VolumeHitPointsTakeTheMediaPhotonsInTheirSphere) {
    const float cell = 0.05f;
    GatherCase c = make_case(cell, 1.0f * cell, 20000, 300, false, 8);
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-1.f, 1.f), u01(0.f, 1.f);
    const size_t surfaces = c.hitpoints.size();
    for (uint32_t i = 0; i < 20000; ++i) {
        dev::Photon p{};
        const bool on_plane = i % 2 == 0;
        p.pos[0] = u(rng), p.pos[1] = on_plane ? 0.f : u(rng), p.pos[2] = u(rng);
        p.normal_oct = oct(0, 1, 0);
        const float wx = u(rng), wy = on_plane ? 0.3f + u01(rng) : u(rng), wz = u(rng);
        const float l = std::sqrt(wx * wx + wy * wy + wz * wz);
        p.wi_oct = oct(wx / l, wy / l, wz / l);
        for (int k = 0; k < 3; ++k) p.flux[k] = 0.1f + 2.f * u01(rng);
        uint32_t bits;
        std::memcpy(&bits, &p.flux[1], sizeof bits);
        bits |= PHOTON_VOLUME_FLAG;
        std::memcpy(&p.flux[1], &bits, sizeof bits);
        p.normal_oct = i % 5 == 0 ? 3 : 0; // its medium (kernels/medium.cl Medium.id): a mesh's, or the world's
        c.photons.push_back(p);
    }
    c.grid.num_photons = uint32_t(c.photons.size());
    c.grid.table_size = 65536;
    c.volume_r2 = 0.12f * 0.12f;
    const float gs[3] = {0.f, 0.6f, -0.3f};
    for (uint32_t i = 0; i < 300; ++i) {
        dev::HitPoint h{};
        h.pos[0] = 0.9f * u(rng), h.pos[1] = 0.9f * u(rng), h.pos[2] = 0.9f * u(rng);
        const float wx = u(rng), wy = u(rng), wz = u(rng), l = std::sqrt(wx * wx + wy * wy + wz * wz);
        h.wo_oct = oct(wx / l, wy / l, wz / l);
        for (int k = 0; k < 3; ++k) h.color[k] = 0.5f + 1.5f * u01(rng), h.weight[k] = 1;
        h.alpha = HITPOINT_VOLUME_ALPHA;
        h.f90 = gs[i % 3];
        h.t_oct = i % 4 == 0 ? 3 : 0; // its medium
        h.pixel = uint32_t(surfaces + i);
        c.hitpoints.push_back(h);
        c.stats.push_back(dev::HitStats{0.01, 0, {0, 0, 0}, {0, 0, 0}});
        c.coverage.push_back(cl_float2{{1.0f, 1.0f}});
    }
    const std::vector<dev::PassFlux> got = device_gather(c), plane = brute_force(c);
    for (size_t i = 0; i < surfaces; ++i) {
        ASSERT_EQ(got[i].m, plane[i].m) << "surface hit point " << i << " took a photon stored in a medium";
        for (int k = 0; k < 3; ++k) ASSERT_EQ(got[i].flux[k], plane[i].flux[k]) << "surface hit point " << i;
    }
    uint64_t total = 0;
    for (size_t i = surfaces; i < c.hitpoints.size(); ++i) {
        const dev::HitPoint& h = c.hitpoints[i];
        double wo[3], want[3] = {0, 0, 0};
        unoct(h.wo_oct, wo);
        uint32_t m = 0;
        for (const dev::Photon& p : c.photons) {
            const float dx = p.pos[0] - h.pos[0], dy = p.pos[1] - h.pos[1], dz = p.pos[2] - h.pos[2];
            if (!photon_in_volume(p) || p.normal_oct != h.t_oct || dx * dx + dy * dy + dz * dz > c.volume_r2)
                continue; // another medium's photons stay there
            double wi[3];
            unoct(p.wi_oct, wi);
            const double g = h.f90, cos_t = -(wi[0] * wo[0] + wi[1] * wo[1] + wi[2] * wo[2]);
            const double d = 1 + g * g - 2 * g * cos_t, phase = (1 - g * g) / (4 * M_PI * d * std::sqrt(d));
            const double flux[3] = {p.flux[0], -p.flux[1], p.flux[2]};
            for (int k = 0; k < 3; ++k) want[k] += flux[k] / h.color[k] * phase;
            ++m;
        }
        total += m;
        ASSERT_EQ(got[i].m, m) << "volume hit point " << i;
        for (int k = 0; k < 3; ++k)
            ASSERT_NEAR(double(got[i].flux[k]) / FLUX_FIXED_SCALE, want[k], 1e-5 * want[k] + 1e-6)
                << "volume hit point " << i << ", channel " << k;
    }
    EXPECT_GT(total, 300u * 10u) << "the volume hit points must actually gather";
}

// The progressive update of kernels/ppm_update.cl against a long-double host reference
// (Hachisuka et al. 2008, Eqs. 7-10), for random photon counts, in 2-D and for PPM's volume hit
// points in 3-D, and far past the point where float accumulators break: N beyond 2^24 after ten
// million passes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "device/kernel_program.h"
#include "shared_types.h"
#include "test_util.h"

using namespace clppm;

namespace {

struct RefStats {
    long double r2, n, tau;
};

// Eqs. 7-10, written out independently of the kernel; a volume hit point's sphere shrinks in
// volume by the ratio, (R'/R)^3 = (N + alpha M) / (N + M).
void reference_update(RefStats& s, long double M, long double tau_M, long double alpha, bool in_volume) {
    if (M == 0) return;
    long double n_new = s.n + alpha * M;
    if (in_volume) {
        const long double r = sqrtl(s.r2) * cbrtl(n_new / (s.n + M));
        s.r2 = r * r;
    } else {
        s.r2 = s.r2 * n_new / (s.n + M);
    }
    s.tau = (s.tau + tau_M) * n_new / (s.n + M);
    s.n = n_new;
}

const char* kLoopKernel = R"CL(
__kernel void many_updates(__global HitStats* stats, __global const uint* M, __global const double* tau_M,
                           uint table, uint steps, double alpha, uint in_volume) {
    uint i = get_global_id(0);
    for (uint k = 0; k < steps; ++k) {
        uint j = (i * 7919u + k) % table;
        ppm_update_stats(&stats[i], (double)M[j], (double3)(tau_M[j], tau_M[j], tau_M[j]), alpha, in_volume != 0);
    }
}
)CL";

struct Run {
    std::vector<dev::HitStats> stats;
};

std::vector<dev::HitStats> run_updates(const std::vector<uint32_t>& M, const std::vector<double>& tau_M, uint32_t items,
                                       uint32_t steps, double alpha, double r0, bool in_volume = false) {
    DeviceContext dc(test::test_device());
    cl::Program program(dc.context, assemble_kernel_source("ppm_update.cl") + kLoopKernel);
    program.build({dc.info.device}, "-cl-std=CL1.2");
    std::vector<dev::HitStats> stats(items, dev::HitStats{r0 * r0, 0, {0, 0, 0}, {0, 0, 0}});
    cl::Buffer sb(dc.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, stats.size() * sizeof(dev::HitStats),
                  stats.data());
    cl::Buffer mb(dc.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, M.size() * sizeof(uint32_t),
                  const_cast<uint32_t*>(M.data()));
    cl::Buffer tb(dc.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, tau_M.size() * sizeof(double),
                  const_cast<double*>(tau_M.data()));
    cl::Kernel k(program, "many_updates");
    k.setArg(0, sb), k.setArg(1, mb), k.setArg(2, tb), k.setArg(3, cl_uint(M.size())), k.setArg(4, cl_uint(steps));
    k.setArg(5, cl_double(alpha)), k.setArg(6, cl_uint(in_volume ? 1 : 0));
    dc.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(items));
    dc.queue.enqueueReadBuffer(sb, CL_TRUE, 0, stats.size() * sizeof(dev::HitStats), stats.data());
    return stats;
}

RefStats run_reference(const std::vector<uint32_t>& M, const std::vector<double>& tau_M, uint32_t item, uint32_t steps,
                       double alpha, double r0, bool in_volume = false) {
    RefStats s{(long double)r0 * r0, 0, 0};
    for (uint32_t k = 0; k < steps; ++k) {
        uint32_t j = (item * 7919u + k) % uint32_t(M.size());
        reference_update(s, M[j], tau_M[j], alpha, in_volume);
    }
    return s;
}

} // namespace

TEST(PpmUpdate, MatchesLongDoubleReferenceForRandomPhotonCounts) {
    std::mt19937 rng(42);
    std::vector<uint32_t> M(997);
    std::vector<double> tau(997);
    for (size_t i = 0; i < M.size(); ++i) {
        M[i] = rng() % 4 == 0 ? 0 : rng() % 1000; // a quarter of the passes find no photon
        tau[i] = M[i] * std::uniform_real_distribution<double>(0.01, 2.0)(rng);
    }
    for (double alpha : {0.01, 0.5, 0.7, 0.99, 1.0}) {
        const uint32_t items = 8, steps = 20000;
        std::vector<dev::HitStats> got = run_updates(M, tau, items, steps, alpha, 0.1);
        for (uint32_t i = 0; i < items; ++i) {
            RefStats ref = run_reference(M, tau, i, steps, alpha, 0.1);
            EXPECT_NEAR(got[i].n / double(ref.n), 1.0, 1e-12) << "alpha " << alpha;
            EXPECT_NEAR(got[i].r2 / double(ref.r2), 1.0, 1e-10) << "alpha " << alpha;
            EXPECT_NEAR(got[i].tau[0] / double(ref.tau), 1.0, 1e-10) << "alpha " << alpha;
            if (alpha == 1.0) {
                EXPECT_EQ(got[i].r2, 0.1 * 0.1) << "alpha 1 is photon mapping: the radius never shrinks";
            }
        }
    }
}

// PPM's fixed volume hit points: the same N and tau, R^3 shrinking by the ratio.
TEST(PpmUpdate, VolumeHitPointsShrinkTheirSphereInVolume) {
    std::mt19937 rng(7);
    std::vector<uint32_t> M(401);
    std::vector<double> tau(401);
    for (size_t i = 0; i < M.size(); ++i) {
        M[i] = rng() % 3 == 0 ? 0 : rng() % 500;
        tau[i] = M[i] * std::uniform_real_distribution<double>(0.01, 2.0)(rng);
    }
    for (double alpha : {0.3, 0.7}) {
        const uint32_t items = 4, steps = 5000;
        std::vector<dev::HitStats> got = run_updates(M, tau, items, steps, alpha, 0.1, true);
        std::vector<dev::HitStats> disc = run_updates(M, tau, items, steps, alpha, 0.1, false);
        for (uint32_t i = 0; i < items; ++i) {
            RefStats ref = run_reference(M, tau, i, steps, alpha, 0.1, true);
            EXPECT_NEAR(got[i].n / double(ref.n), 1.0, 1e-12) << "alpha " << alpha;
            EXPECT_NEAR(got[i].r2 / double(ref.r2), 1.0, 1e-9) << "alpha " << alpha;
            EXPECT_NEAR(got[i].tau[0] / double(ref.tau), 1.0, 1e-10) << "alpha " << alpha;
            // R^3 / R_0^3 is the disc's R^2 / R_0^2: the same product of ratios.
            EXPECT_NEAR(std::pow(got[i].r2 / 0.01, 1.5) / (disc[i].r2 / 0.01), 1.0, 1e-9);
            EXPECT_EQ(got[i].tau[0], disc[i].tau[0]) << "tau does not depend on the dimension";
        }
    }
}

// Ten million passes of 10 photons: N passes 2^24 and keeps counting; R^2 follows the product of
// the ratios; nothing underflows to zero or turns NaN.
TEST(PpmUpdate, TenMillionPassesKeepPrecisionBeyond2To24) {
    std::vector<uint32_t> M{10};
    std::vector<double> tau{10.0};
    const uint32_t steps = 10000000;
    const double alpha = 0.7;
    std::vector<dev::HitStats> got = run_updates(M, tau, 1, steps, alpha, 1.0);
    RefStats ref = run_reference(M, tau, 0, steps, alpha, 1.0);
    EXPECT_GT(got[0].n, double(1 << 24) * 4);
    EXPECT_NEAR(got[0].n, 7e7, 1e-3); // exactly alpha * M per pass
    EXPECT_NEAR(got[0].r2 / double(ref.r2), 1.0, 1e-8);
    EXPECT_NEAR(got[0].tau[0] / double(ref.tau), 1.0, 1e-8);
    EXPECT_GT(got[0].r2, 0.0);
    EXPECT_TRUE(std::isfinite(got[0].tau[0]));
    // With every photon carrying flux 1, tau' = (tau + M)(N + aM)/(N + M) keeps tau = N exactly:
    // the accumulated flux per counted photon must not drift over ten million passes.
    EXPECT_NEAR(got[0].tau[0] / got[0].n, 1.0, 1e-9);
}

// The MIS weights of vertex connection and merging (kernels/vcm_mis.h, the code the kernels run)
// against their closed form on enumerated paths: for a random path x_0 (on a light) ... x_k (the
// camera) with random densities, every technique's weight from the recursive partial sums equals
// p_t^2 / sum_u p_u^2 with p_t the technique's path density written out vertex by vertex
// (Georgiev et al. 2012, Eqs. 10-12 with n_VM = N_L, n_LT = N_L), and the weights sum to one.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "vcm_mis.h"

namespace {

struct V3 {
    double x, y, z;
};
V3 sub(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 unit(V3 a) {
    const double l = std::sqrt(dot(a, a));
    return {a.x / l, a.y / l, a.z / l};
}

// A path with everything the techniques' densities need.
struct Path {
    int k = 0;                  // segments; vertices x_0 .. x_k
    std::vector<V3> x, n;       // positions, normals
    std::vector<double> pL, pC; // at interior vertex j: solid-angle density of sampling x_{j+1}
                                // from x_{j-1} (light direction), and x_{j-1} from x_{j+1}
    double pA0 = 0, pdir0 = 0;  // the light: point density, emission direction density
    double cam_w = 0;           // the pixel's solid-angle density towards x_{k-1}
    double d2(int a, int b) const { return dot(sub(x[a], x[b]), sub(x[a], x[b])); }
    // |cos| at x_a towards x_b.
    double cos(int a, int b) const { return std::fabs(dot(n[a], unit(sub(x[b], x[a])))); }
};

Path random_path(int k, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1, 1), pdf(0.05, 3.0);
    Path p;
    p.k = k;
    for (int j = 0; j <= k; ++j) {
        p.x.push_back({u(rng) * 2, u(rng) * 2, u(rng) * 2});
        p.n.push_back(unit({u(rng), u(rng), u(rng) + 0.01}));
        p.pL.push_back(pdf(rng));
        p.pC.push_back(pdf(rng));
    }
    p.pA0 = pdf(rng);
    p.pdir0 = pdf(rng);
    p.cam_w = pdf(rng) * 10;
    return p;
}

// Area densities: forward (from the light) and backward (from the camera) of vertex j.
double fwd(const Path& p, int j) {
    if (j == 0) return p.pA0;
    if (j == 1) return p.pdir0 * p.cos(1, 0) / p.d2(0, 1);
    return p.pL[size_t(j - 1)] * p.cos(j, j - 1) / p.d2(j - 1, j);
}
double bwd(const Path& p, int j) {
    if (j == p.k - 1) return p.cam_w * p.cos(j, p.k) / p.d2(j, p.k);
    return p.pC[size_t(j + 1)] * p.cos(j, j + 1) / p.d2(j, j + 1);
}

// The closed form: densities of the connection techniques s = 0..k (s light vertices; s = k is
// light tracing, N_L samples) and of merging at x_1 .. x_{k-1}.
struct Closed {
    std::vector<double> conn, merge; // merge[i] for vertex i (merge[0] unused)
};
Closed closed_form(const Path& p, double light_paths, double eta) {
    Closed c;
    for (int s = 0; s <= p.k; ++s) {
        double d = 1;
        for (int j = 0; j < s; ++j) d *= fwd(p, j);
        for (int j = s; j < p.k; ++j) d *= bwd(p, j);
        c.conn.push_back(s == p.k ? light_paths * d : d);
    }
    c.merge.assign(size_t(p.k), 0.0);
    for (int i = 1; i < p.k; ++i) {
        double d = eta * fwd(p, i);
        for (int j = 0; j < i; ++j) d *= fwd(p, j);
        for (int j = i; j < p.k; ++j) d *= bwd(p, j);
        c.merge[size_t(i)] = d;
    }
    return c;
}

// The sub-paths' partial sums at every vertex, as the kernels build them.
struct States {
    std::vector<VcmMis> light, camera; // light[j]: at x_j after reaching it; camera[j] likewise
};
States recursive(const Path& p, double light_paths, float vm, float vc) {
    States st;
    st.light.resize(size_t(p.k + 1));
    st.camera.resize(size_t(p.k + 1));
    VcmMis m = vcm_light_start(float(p.pA0 * p.pdir0), float(p.pA0), float(p.cos(0, 1)), false, true, vc);
    for (int j = 1; j <= p.k - 1; ++j) {
        vcm_on_hit(&m, float(p.d2(j - 1, j)), float(p.cos(j, j - 1)), false);
        st.light[size_t(j)] = m;
        vcm_on_scatter(&m, float(p.cos(j, j + 1)), float(p.pL[size_t(j)]), float(p.pC[size_t(j)]), false, vm, vc);
    }
    m = vcm_camera_start(float(p.cam_w), float(light_paths));
    for (int j = p.k - 1; j >= 0; --j) {
        vcm_on_hit(&m, float(p.d2(j + 1, j)), float(p.cos(j, j + 1)), false);
        st.camera[size_t(j)] = m;
        if (j > 0)
            vcm_on_scatter(&m, float(p.cos(j, j - 1)), float(p.pC[size_t(j)]), float(p.pL[size_t(j)]), false, vm, vc);
    }
    return st;
}

} // namespace

TEST(VcmMis, WeightsEqualTheClosedFormAndSumToOne) {
    std::mt19937 rng(7);
    const double light_paths = 4096;
    for (int trial = 0; trial < 400; ++trial) {
        const int k = 2 + trial % 5;
        const Path p = random_path(k, rng);
        for (bool merging : {true, false}) {
            // eta = pi r^2 N_L: VCM with merging, BPT without (vm_factor 0).
            const double eta = merging ? 0.01 + 2.0 * (trial % 7) : 0.0;
            const float vm = merging ? vcm_mis(float(eta)) : 0.f, vc = merging ? vcm_mis(float(1 / eta)) : 0.f;
            const Closed c = closed_form(p, light_paths, eta);
            double total2 = 0;
            for (double d : c.conn) total2 += d * d;
            for (double d : c.merge) total2 += d * d;
            const States st = recursive(p, light_paths, vm, vc);

            std::vector<double> got(c.conn.size()), got_merge(c.merge.size(), 0.0);
            // s = 0: the camera sub-path finds the light at x_0.
            got[0] = vcm_weight_emission(&st.camera[0], float(p.pA0), float(p.pA0 * p.pdir0));
            // s = 1: a light sample from x_1 (camera vertex) picks x_0.
            got[1] = vcm_weight_light_sample(&st.camera[1], float(p.pA0 * p.d2(0, 1) / p.cos(0, 1)),
                                             float(p.pA0 * p.pdir0), float(p.cos(0, 1)), false, float(p.pC[1]),
                                             float(p.pL[1]), float(p.cos(1, 0)), vm);
            // s, t >= 2: light vertex x_{s-1} to camera vertex x_s.
            for (int s = 2; s <= k - 1; ++s) {
                const double g = 1.0 / p.d2(s - 1, s);
                got[size_t(s)] = vcm_weight_connection(
                    &st.camera[size_t(s)], &st.light[size_t(s - 1)], float(p.pC[size_t(s)] * p.cos(s - 1, s) * g),
                    float(p.pL[size_t(s)]), float(p.pL[size_t(s - 1)] * p.cos(s, s - 1) * g),
                    float(p.pC[size_t(s - 1)]), vm);
            }
            // t = 1: light vertex x_{k-1} to the camera.
            if (k >= 2)
                got[size_t(k)] = vcm_weight_camera_connection(&st.light[size_t(k - 1)], float(bwd(p, k - 1)),
                                                              float(light_paths), float(p.pC[size_t(k - 1)]), vm);
            // Merging at x_i.
            if (merging)
                for (int i = 1; i < k; ++i)
                    got_merge[size_t(i)] = vcm_weight_merge(&st.camera[size_t(i)], &st.light[size_t(i)],
                                                            float(p.pC[size_t(i)]), float(p.pL[size_t(i)]), vc);
            double sum = 0;
            for (size_t s = 0; s < got.size(); ++s) {
                const double want = c.conn[s] * c.conn[s] / total2;
                EXPECT_NEAR(got[s], want, 2e-4 * (1 + want)) << "trial " << trial << " k " << k << " s " << s;
                sum += got[s];
            }
            for (size_t i = 1; i < got_merge.size(); ++i) {
                const double want = c.merge[i] * c.merge[i] / total2;
                EXPECT_NEAR(got_merge[i], want, 2e-4 * (1 + want)) << "trial " << trial << " k " << k << " merge " << i;
                sum += got_merge[i];
            }
            EXPECT_NEAR(sum, 1.0, 1e-3) << "trial " << trial << " k " << k << " merging " << merging;
        }
    }
}

// A delta lobe: the sub-paths' sums skip the vertex (no technique can end there), and the weights of
// the techniques that remain still sum to one.
TEST(VcmMis, ADeltaVertexDropsItsTechniques) {
    std::mt19937 rng(11);
    for (int trial = 0; trial < 100; ++trial) {
        Path p = random_path(3, rng); // x_0 light, x_1 diffuse, x_2 a mirror, x_3 camera
        const double light_paths = 1000, eta = 0.5;
        const float vm = vcm_mis(float(eta)), vc = vcm_mis(float(1 / eta));
        // Closed form without the techniques that need x_2 as an endpoint: s = 0 (camera hits x_0
        // via x_2 then x_1), s = 1 (light sample from x_1), merging at x_1. x_2's direction
        // densities are deltas that cancel: p_fwd(x_2 -> x_3) and p_bwd(x_2 -> x_1) are taken as
        // their cosine-weighted delta (the same in every remaining technique).
        const double a1 = fwd(p, 0), b0 = p.pC[1] * p.cos(0, 1) / p.d2(0, 1);
        const double f1 = fwd(p, 1);
        const double b1 = 1.0 / p.d2(1, 2); // the camera's reach of x_1 through the mirror, up to common factors
        const double ps0 = b0 * b1, ps1 = a1 * b1, pvm = eta * a1 * f1 * b1;
        const double t2 = ps0 * ps0 + ps1 * ps1 + pvm * pvm;
        // Recursion: camera start, hit x_2 (mirror): delta scatter towards x_1, hit x_1.
        VcmMis c = vcm_camera_start(float(p.cam_w), float(light_paths));
        vcm_on_hit(&c, float(p.d2(3, 2)), float(p.cos(2, 3)), false);
        vcm_on_scatter(&c, float(p.cos(2, 1)), 0.f, 0.f, true, vm, vc);
        vcm_on_hit(&c, float(p.d2(2, 1)), float(p.cos(1, 2)), false);
        const VcmMis at1 = c;
        vcm_on_scatter(&c, float(p.cos(1, 0)), float(p.pC[1]), float(p.pL[1]), false, vm, vc);
        vcm_on_hit(&c, float(p.d2(1, 0)), float(p.cos(0, 1)), false);
        VcmMis l = vcm_light_start(float(p.pA0 * p.pdir0), float(p.pA0), float(p.cos(0, 1)), false, true, vc);
        vcm_on_hit(&l, float(p.d2(0, 1)), float(p.cos(1, 0)), false);
        const double w0 = vcm_weight_emission(&c, float(p.pA0), float(p.pA0 * p.pdir0));
        const double w1 =
            vcm_weight_light_sample(&at1, float(p.pA0 * p.d2(0, 1) / p.cos(0, 1)), float(p.pA0 * p.pdir0),
                                    float(p.cos(0, 1)), false, float(p.pC[1]), float(p.pL[1]), float(p.cos(1, 0)), vm);
        const double wm = vcm_weight_merge(&at1, &l, float(p.pC[1]), float(p.pL[1]), vc);
        EXPECT_NEAR(w0 + w1 + wm, 1.0, 1e-3) << trial;
        EXPECT_NEAR(w0, ps0 * ps0 / t2, 2e-4) << trial;
        EXPECT_NEAR(w1, ps1 * ps1 / t2, 2e-4) << trial;
        EXPECT_NEAR(wm, pvm * pvm / t2, 2e-4) << trial;
    }
}

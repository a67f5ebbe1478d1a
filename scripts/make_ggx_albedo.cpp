// Writes kernels/ggx_albedo.h: the directional albedo of the GGX microfacet reflection lobe
// (height-correlated Smith G2, Heitz 2014 Eq. 99) that kernels/bsdf.cl needs for energy
// conservation. With Schlick's Fresnel F = F0 + (F90 - F0) (1 - wo.h)^5 the albedo is linear in
// F0 and F90, so two tables over (cos_o, alpha) give it for any colour:
//   A(mu, alpha) = int D G2 / (4 mu) dwi            (F = 1: the lobe's own energy)
//   B(mu, alpha) = int (1 - wo.h)^5 D G2 / (4 mu) dwi
//   E(mu) = F0 A + (F90 - F0) B.
// tabulated over cos_o and roughness (alpha = roughness^2), and their cosine-weighted
// hemispherical means A_avg, B_avg (2 int E mu dmu) of the bilinear interpolant kernels/albedo_table.cl uses, so that the coupled diffuse term integrates exactly.
//
// Build and run (deterministic: rerunning writes the same bytes):
//   g++ -O2 -std=c++17 scripts/make_ggx_albedo.cpp -o /tmp/make_ggx_albedo && /tmp/make_ggx_albedo > kernels/ggx_albedo.h
// tests/bsdf_model_test.cpp checks entries against an independent quadrature over wi.
#include <cmath>
#include <cstdio>
#include <vector>

namespace {

constexpr int kMu = 32, kAlpha = 32;

double lambda(double c, double a) { return 0.5 * (-1 + std::sqrt(1 + a * a * (1 - c * c) / (c * c))); }

// Integrates over half vectors h with tan^2(theta_h) = a^2 u / (1 - u), so D cos_h dw_h =
// du dphi / (2 pi); wi = reflect(wo, h), dw_i = 4 (wo.h) dw_h. wo = (sqrt(1 - mu^2), 0, mu).
// For each phi the valid u (wo.h > 0 and wi above the horizon) are [0, u_c): u_c is found by
// bisection and [0, u_c) integrated by Gauss-Legendre panels, so the horizon costs no accuracy
// (a plain grid over u converges only as 1 / N there).
const double kGlX[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281, 0.9305681557970263};
const double kGlW[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731, 0.1739274225687269};

struct Half {
    double oh, wiz, ch;
};
Half half(double mu, double a, double u, double phi) {
    double tan2 = a * a * u / (1 - u), ch = 1 / std::sqrt(1 + tan2), sh = std::sqrt(std::max(0.0, 1 - ch * ch));
    double oh = std::sqrt(1 - mu * mu) * sh * std::cos(phi) + mu * ch;
    return {oh, 2 * oh * ch - mu, ch};
}
bool valid(double mu, double a, double u, double phi) {
    Half h = half(mu, a, u, phi);
    return h.oh > 0 && h.wiz > 0;
}

void albedo(double mu, double a, double* A, double* B) {
    double sa = 0, sb = 0;
    const int kPhi = 256, kU = 64;
    for (int j = 0; j < kPhi; ++j)
        for (int q = 0; q < 4; ++q) {
            double phi = M_PI * (j + kGlX[q]) / kPhi, wphi = kGlW[q] * M_PI / kPhi * 2; // symmetric in phi
            // u_c: scan for the first invalid u, then bisect.
            double lo = 0, hi = 1;
            const int scan = 4096;
            for (int k = 1; k <= scan; ++k) {
                double u = double(k) / scan * (1 - 1e-12);
                if (!valid(mu, a, u, phi)) {
                    hi = u;
                    break;
                }
                lo = u;
            }
            if (hi < 1)
                for (int it = 0; it < 60; ++it) {
                    double m = 0.5 * (lo + hi);
                    (valid(mu, a, m, phi) ? lo : hi) = m;
                }
            double uc = hi < 1 ? lo : 1.0;
            for (int p = 0; p < kU; ++p)
                for (int r = 0; r < 4; ++r) {
                    double u = uc * (p + kGlX[r]) / kU, wu = kGlW[r] * uc / kU;
                    Half h = half(mu, a, u, phi);
                    if (h.oh <= 0 || h.wiz <= 0) continue;
                    double g2 = 1 / (1 + lambda(mu, a) + lambda(h.wiz, a));
                    // f cos_i dw_i = D G2 / (4 mu) * 4 oh dw_h, and dw_h = du dphi / (2 pi D ch)
                    double w = g2 * h.oh / (mu * h.ch) / (2 * M_PI) * wu * wphi;
                    double s = 1 - h.oh, s5 = s * s * s * s * s;
                    sa += w;
                    sb += w * s5;
                }
        }
    *A = sa;
    *B = sb;
}

double lerp_mu(const std::vector<double>& t, int j, double mu) {
    double x = std::fmin(std::fmax(mu * kMu - 0.5, 0.0), kMu - 1.0);
    int i = std::min(int(x), kMu - 2);
    double f = x - i;
    return t[j * kMu + i] * (1 - f) + t[j * kMu + i + 1] * f;
}

void print(const char* name, const std::vector<double>& v, int per_line) {
    std::printf("CLPPM_GGX_TABLE float %s[%zu] = {\n", name, v.size());
    for (size_t i = 0; i < v.size(); ++i)
        std::printf("%s%.9ef,%s", i % per_line ? " " : "    ", v[i], (i + 1) % per_line ? "" : "\n");
    std::printf("};\n");
}

} // namespace

int main() {
    std::vector<double> A(kMu * kAlpha), B(kMu * kAlpha), Aavg(kAlpha), Bavg(kAlpha);
    for (int j = 0; j < kAlpha; ++j) {
        double r = double(j) / (kAlpha - 1), a = r * r; // rows by roughness: dense where alpha is small
        for (int i = 0; i < kMu; ++i) {
            double mu = (i + 0.5) / kMu;
            if (j == 0) { // a mirror: all energy, Schlick at the view angle
                A[j * kMu + i] = 1;
                B[j * kMu + i] = std::pow(1 - mu, 5);
            } else {
                albedo(mu, a, &A[j * kMu + i], &B[j * kMu + i]);
            }
        }
        double sa = 0, sb = 0;
        const int n = 1 << 16;
        for (int k = 0; k < n; ++k) {
            double mu = (k + 0.5) / n;
            sa += 2 * mu * lerp_mu(A, j, mu) / n;
            sb += 2 * mu * lerp_mu(B, j, mu) / n;
        }
        Aavg[j] = sa;
        Bavg[j] = sb;
    }
    std::printf("/* ggx_albedo.h: generated by scripts/make_ggx_albedo.cpp (see there); do not edit.\n"
                " * Row j is roughness j / (GGX_ALBEDO_ALPHA - 1), alpha its square; column i is cos_o = (i + 0.5) / GGX_ALBEDO_MU. */\n"
                "#ifndef CLPPM_GGX_ALBEDO_H\n#define CLPPM_GGX_ALBEDO_H\n\n"
                "#ifdef __OPENCL_VERSION__\n#define CLPPM_GGX_TABLE __constant\n#else\n"
                "#define CLPPM_GGX_TABLE inline const\n#endif\n\n"
                "#define GGX_ALBEDO_MU %d\n#define GGX_ALBEDO_ALPHA %d\n\n",
                kMu, kAlpha);
    print("ggx_albedo_a", A, 8);
    print("ggx_albedo_b", B, 8);
    print("ggx_albedo_a_avg", Aavg, 8);
    print("ggx_albedo_b_avg", Bavg, 8);
    std::printf("\n#endif\n");
}

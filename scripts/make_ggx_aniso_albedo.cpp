// Writes kernels/ggx_aniso_albedo.h: an upper bound of the directional albedo E(wo) of the
// anisotropic GGX reflection lobe (F = 1, height-correlated Smith G2; Heitz 2014) over
// (cos_o, the azimuth of wo from the stretched direction, alpha across, the stretch), and the
// cosine-weighted hemispherical mean of that bound, for the Kulla-Conty multiple-scattering term of
// a stretched metal in kernels/bsdf.cl:
//   f_ms = F_ms (1 - E(wo)) (1 - E(wi)) / (pi (1 - E_avg)).
// Its integral over wi is F_ms (1 - E(wo)) exactly (E_avg is the mean of the same interpolant);
// with E at least the true albedo, the lobe and the term together never exceed F_ms + what the
// lobe keeps, so a white stretched metal never gains, and loses only what the bound overstates.
//
// Grid: cos_o = (i / (MU - 1))^2; azimuth = j / (PHI - 1) * pi / 2 (the lobe is symmetric in both
// axes); alpha = max(r^2, 0.001), r = k / (ALPHA - 1) (rows by roughness); alpha_t = alpha + (1 -
// alpha) t, t = l / (T - 1). The nodes hold the albedo, raised where needed so that the
// multilinear interpolant lies above the albedo (plus 0.002 for the quadrature) on a grid twice as
// fine: an upper bound, up to the curvature between those samples. Albedos by the visible-normal distribution (Heitz
// 2018) on a midpoint grid of 160 x 160 uniforms: E = mean of G2 / G1 over reflected directions
// above the horizon.
//
// Build and run (deterministic: rerunning writes the same bytes):
//   g++ -O2 -std=c++17 scripts/make_ggx_aniso_albedo.cpp -o /tmp/make_ggx_aniso_albedo &&
//     /tmp/make_ggx_aniso_albedo > kernels/ggx_aniso_albedo.h
// tests/bsdf_model_test.cpp checks entries against an independent quadrature over wi.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace {

constexpr int kMu = 16, kPhi = 5, kAlpha = 8, kT = 6;
constexpr int kFine = 2; // fine samples per cell and axis

struct V {
    double x, y, z;
};
V norm(V v) {
    double l = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    return {v.x / l, v.y / l, v.z / l};
}
V cross(V a, V b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

double lambda(V v, double ax, double ay) {
    return 0.5 * (-1 + std::sqrt(1 + (ax * ax * v.x * v.x + ay * ay * v.y * v.y) / (v.z * v.z)));
}

// E(wo) for alpha ax along x, ay along y.
double albedo(double mu, double phi, double ax, double ay) {
    mu = std::max(mu, 1e-4);
    const double st = std::sqrt(1 - mu * mu);
    const V wo{st * std::cos(phi), st * std::sin(phi), mu};
    const V vh = norm({ax * wo.x, ay * wo.y, wo.z});
    const double lensq = vh.x * vh.x + vh.y * vh.y;
    const V t1 = lensq > 0 ? V{-vh.y / std::sqrt(lensq), vh.x / std::sqrt(lensq), 0} : V{1, 0, 0};
    const V t2 = cross(vh, t1);
    const double lo = lambda(wo, ax, ay);
    const int n = 160;
    double sum = 0;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            const double u1 = (a + 0.5) / n, u2 = (b + 0.5) / n;
            const double r = std::sqrt(u1), ph = 2 * M_PI * u2;
            double p1 = r * std::cos(ph), p2 = r * std::sin(ph);
            const double s = 0.5 * (1 + vh.z);
            p2 = (1 - s) * std::sqrt(std::max(0.0, 1 - p1 * p1)) + s * p2;
            const double p3 = std::sqrt(std::max(0.0, 1 - p1 * p1 - p2 * p2));
            const V nh{p1 * t1.x + p2 * t2.x + p3 * vh.x, p1 * t1.y + p2 * t2.y + p3 * vh.y,
                       p1 * t1.z + p2 * t2.z + p3 * vh.z};
            const V h = norm({ax * nh.x, ay * nh.y, std::max(1e-9, nh.z)});
            const double oh = wo.x * h.x + wo.y * h.y + wo.z * h.z;
            const V wi{2 * oh * h.x - wo.x, 2 * oh * h.y - wo.y, 2 * oh * h.z - wo.z};
            if (wi.z <= 0) continue;
            sum += (1 + lo) / (1 + lo + lambda(wi, ax, ay));
        }
    return sum / (double(n) * n);
}

double mu_at(double x) { return (x / (kMu - 1)) * (x / (kMu - 1)); } // dense at grazing, where E bends
double phi_at(double x) { return x / (kPhi - 1) * M_PI / 2; }
double alpha_at(double x) {
    const double r = x / (kAlpha - 1);
    return std::max(r * r, 1e-3);
}
double t_at(double x) { return x / (kT - 1); }

int idx(int i, int j, int k, int l) { return ((l * kAlpha + k) * kPhi + j) * kMu + i; }

// The multilinear interpolant of table t at fractional indices.
double interp(const std::vector<double>& t, double x, double y, double z, double w) {
    const int i = std::min(int(x), kMu - 2), j = std::min(int(y), kPhi - 2), k = std::min(int(z), kAlpha - 2),
              l = std::min(int(w), kT - 2);
    const double fx = x - i, fy = y - j, fz = z - k, fw = w - l;
    double v = 0;
    for (int c = 0; c < 16; ++c) {
        const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1, dl = (c >> 3) & 1;
        const double wgt = (di ? fx : 1 - fx) * (dj ? fy : 1 - fy) * (dk ? fz : 1 - fz) * (dl ? fw : 1 - fw);
        v += wgt * t[idx(i + di, j + dj, k + dk, l + dl)];
    }
    return v;
}

} // namespace

int main() {
    // The albedo on the fine grid.
    const int fm = (kMu - 1) * kFine + 1, fp = (kPhi - 1) * kFine + 1, fa = (kAlpha - 1) * kFine + 1,
              ft = (kT - 1) * kFine + 1;
    std::vector<double> fine(size_t(fm) * fp * fa * ft);
    auto fidx = [&](int i, int j, int k, int l) { return ((size_t(l) * fa + k) * fp + j) * fm + i; };
    for (int l = 0; l < ft; ++l)
        for (int k = 0; k < fa; ++k) {
            const double a = alpha_at(double(k) / kFine), at = a + (1 - a) * t_at(double(l) / kFine);
            for (int j = 0; j < fp; ++j)
                for (int i = 0; i < fm; ++i)
                    fine[fidx(i, j, k, l)] =
                        albedo(mu_at(double(i) / kFine), phi_at(double(j) / kFine), at, a);
        }
    // The nodes: the albedo there, then raised until the interpolant lies above every fine sample
    // (plus 0.002 for the quadrature): where a cell's interpolant falls short of a sample, its 16
    // corners rise by the shortfall, which lifts the interpolant there by exactly that much.
    std::vector<double> table(size_t(kMu) * kPhi * kAlpha * kT);
    for (int l = 0; l < kT; ++l)
        for (int k = 0; k < kAlpha; ++k)
            for (int j = 0; j < kPhi; ++j)
                for (int i = 0; i < kMu; ++i)
                    table[idx(i, j, k, l)] = fine[fidx(i * kFine, j * kFine, k * kFine, l * kFine)] + 0.002;
    for (int pass = 0; pass < 100; ++pass) {
        double worst = 0;
        for (int l = 0; l < ft; ++l)
            for (int k = 0; k < fa; ++k)
                for (int j = 0; j < fp; ++j)
                    for (int i = 0; i < fm; ++i) {
                        const double x = double(i) / kFine, y = double(j) / kFine, z = double(k) / kFine,
                                     w = double(l) / kFine;
                        const double d = fine[fidx(i, j, k, l)] + 0.002 - interp(table, x, y, z, w);
                        if (d <= 1e-9) continue;
                        worst = std::max(worst, d);
                        const int ci = std::min(int(x), kMu - 2), cj = std::min(int(y), kPhi - 2),
                                  ck = std::min(int(z), kAlpha - 2), cl = std::min(int(w), kT - 2);
                        for (int c = 0; c < 16; ++c)
                            table[idx(ci + (c & 1), cj + ((c >> 1) & 1), ck + ((c >> 2) & 1), cl + ((c >> 3) & 1))] += d;
                    }
        if (worst <= 1e-9) break;
    }
    for (double& v : table) v = std::min(v, 1.0);
    // The cosine-weighted mean of the interpolant: 2 int mu (2 / pi) int E dphi dmu.
    std::vector<double> avg(size_t(kAlpha) * kT);
    for (int l = 0; l < kT; ++l)
        for (int k = 0; k < kAlpha; ++k) {
            double s = 0;
            const int nm = 512, np = 64;
            for (int a = 0; a < nm; ++a)
                for (int b = 0; b < np; ++b) {
                    const double mu = (a + 0.5) / nm, y = (b + 0.5) / np * (kPhi - 1);
                    s += 2 * mu * interp(table, std::sqrt(mu) * (kMu - 1), y, k, l) / (double(nm) * np);
                }
            avg[size_t(l) * kAlpha + k] = s;
        }
    std::printf("/* ggx_aniso_albedo.h: generated by scripts/make_ggx_aniso_albedo.cpp (see there); do not edit.\n"
                " * ggx_aniso_albedo[((l * GGX_ANISO_ALPHA + k) * GGX_ANISO_PHI + j) * GGX_ANISO_MU + i]: cos_o = (i /\n"
                " * (MU - 1))^2, azimuth from the stretched direction j / (PHI - 1) pi / 2, alpha across = max(r^2, 0.001)\n"
                " * with r = k / (ALPHA - 1), alpha along = alpha + (1 - alpha) l / (T - 1). */\n"
                "#ifndef CLPPM_GGX_ANISO_ALBEDO_H\n#define CLPPM_GGX_ANISO_ALBEDO_H\n\n"
                "#ifdef __OPENCL_VERSION__\n#define CLPPM_GGX_ANISO_TABLE __constant\n#else\n"
                "#define CLPPM_GGX_ANISO_TABLE inline const\n#endif\n\n"
                "#define GGX_ANISO_MU %d\n#define GGX_ANISO_PHI %d\n#define GGX_ANISO_ALPHA %d\n#define GGX_ANISO_T %d\n\n",
                kMu, kPhi, kAlpha, kT);
    auto print = [](const char* name, const std::vector<double>& v) {
        std::printf("CLPPM_GGX_ANISO_TABLE float %s[%zu] = {\n", name, v.size());
        for (size_t i = 0; i < v.size(); ++i)
            std::printf("%s%.7ef,%s", i % 7 ? " " : "    ", v[i], (i + 1) % 7 ? "" : "\n"); // as clang-format packs them
        if (v.size() % 7) std::printf("\n");
        std::printf("};\n");
    };
    print("ggx_aniso_albedo", table);
    print("ggx_aniso_albedo_avg", avg);
    std::printf("\n#endif\n");
}

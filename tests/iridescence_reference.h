// A host reference of kernels/iridescence.cl in double, written from Belcour and Barla 2017 and
// the KHR_materials_iridescence specification's evaluation (shared by iridescence_test.cpp and
// bsdf_model_test.cpp), and the exact spectral Airy reflectance it approximates.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>

namespace clppm::test {

using Rgb = std::array<double, 3>;

inline Rgb ref_irid_sensitivity(double opd, const Rgb& shift) {
    const double phase = 2 * M_PI * opd * 1e-9;
    const double val[3] = {5.4856e-13, 4.4201e-13, 5.2481e-13}, pos[3] = {1.6810e+06, 1.7953e+06, 2.2084e+06};
    const double var[3] = {4.3278e+09, 9.3046e+09, 6.6121e+09};
    double xyz[3];
    for (int k = 0; k < 3; ++k)
        xyz[k] = val[k] * std::sqrt(2 * M_PI * var[k]) * std::cos(pos[k] * phase + shift[size_t(k)]) *
                 std::exp(-phase * phase * var[k]);
    xyz[0] += 9.7470e-14 * std::sqrt(2 * M_PI * 4.5282e+09) * std::cos(2.2399e+06 * phase + shift[0]) *
              std::exp(-4.5282e+09 * phase * phase);
    for (double& v : xyz) v /= 1.0685e-7;
    return {3.2404542 * xyz[0] - 1.5371385 * xyz[1] - 0.4985314 * xyz[2],
            -0.9692660 * xyz[0] + 1.8760108 * xyz[1] + 0.0415560 * xyz[2],
            0.0556434 * xyz[0] - 0.2040259 * xyz[1] + 1.0572252 * xyz[2]};
}

inline double ref_schlick(double f0, double c) { return f0 + (1 - f0) * std::pow(std::clamp(1 - c, 0.0, 1.0), 5); }

// The film's reflectance over a base of Fresnel reflectance f0, seen from index 1 at cos1.
inline Rgb ref_irid_fresnel(double eta2, double d, double cos1, const Rgb& f0) {
    const double t = std::clamp(d / 0.03, 0.0, 1.0), eta = 1 + (eta2 - 1) * t * t * (3 - 2 * t);
    const double cos2sq = 1 - (1 - cos1 * cos1) / (eta * eta);
    if (cos2sq < 0) return {1, 1, 1};
    const double cos2 = std::sqrt(cos2sq);
    const double r0 = (eta - 1) / (eta + 1), R12 = ref_schlick(r0 * r0, cos1), T121 = 1 - R12;
    const double phi21 = M_PI - (eta < 1 ? M_PI : 0.0);
    Rgb R23, phi, I;
    for (size_t k = 0; k < 3; ++k) {
        const double s = std::sqrt(std::clamp(f0[k], 0.0, 0.9999)), n3 = (1 + s) / (1 - s);
        const double r1 = (n3 - eta) / (n3 + eta);
        R23[k] = ref_schlick(r1 * r1, cos2);
        phi[k] = phi21 + (n3 < eta ? M_PI : 0.0);
    }
    const double opd = 2 * eta * d * cos2;
    Rgb cm, r123;
    for (size_t k = 0; k < 3; ++k) {
        const double R123 = std::clamp(R12 * R23[k], 1e-5, 0.9999);
        r123[k] = std::sqrt(R123);
        const double Rs = T121 * T121 * R23[k] / (1 - R123);
        I[k] = R12 + Rs;
        cm[k] = Rs - T121;
    }
    for (int m = 1; m <= 2; ++m) {
        Rgb shift{m * phi[0], m * phi[1], m * phi[2]};
        Rgb s = ref_irid_sensitivity(m * opd, shift);
        for (size_t k = 0; k < 3; ++k) {
            cm[k] *= r123[k];
            I[k] += cm[k] * 2 * s[k];
        }
    }
    for (double& v : I) v = std::max(v, 0.0);
    return I;
}

// CIE 1931 colour matching functions, Wyman, Sloan and Shirley 2013 (multi-lobe fit).
inline double cie_lobe(double l, double mu, double s1, double s2) {
    const double t = (l - mu) / (l < mu ? s1 : s2);
    return std::exp(-0.5 * t * t);
}
inline std::array<double, 3> cie_xyz(double l) {
    return {1.056 * cie_lobe(l, 599.8, 37.9, 31.0) + 0.362 * cie_lobe(l, 442.0, 16.0, 26.7) -
                0.065 * cie_lobe(l, 501.1, 20.4, 26.2),
            0.821 * cie_lobe(l, 568.8, 46.9, 40.5) + 0.286 * cie_lobe(l, 530.9, 16.3, 31.1),
            1.217 * cie_lobe(l, 437.0, 11.8, 36.0) + 0.681 * cie_lobe(l, 459.0, 26.0, 13.8)};
}

// The exact reflectance at normal incidence of a film of index n2 and thickness d (nm) between
// air and a base of index n3 (Airy's formula, both interfaces by Fresnel's amplitudes), averaged
// over the visible spectrum with the CIE functions and taken to linear Rec. 709, white balanced so
// that a reflectance of 1 at every wavelength is (1, 1, 1), as the approximation's constant
// term is.
inline Rgb airy_rgb_normal(double n2, double n3, double d) {
    const double r12 = (1 - n2) / (1 + n2), r23 = (n2 - n3) / (n2 + n3);
    std::array<double, 3> xyz{0, 0, 0}, white{0, 0, 0};
    for (double l = 360; l <= 830; l += 0.5) {
        const std::complex<double> e = std::polar(1.0, 4 * M_PI * n2 * d / l);
        const double R = std::norm((r12 + r23 * e) / (1.0 + r12 * r23 * e));
        const auto c = cie_xyz(l);
        for (size_t k = 0; k < 3; ++k) xyz[k] += R * c[k], white[k] += c[k];
    }
    auto to_rgb = [](const std::array<double, 3>& v) {
        return Rgb{3.2404542 * v[0] - 1.5371385 * v[1] - 0.4985314 * v[2],
                   -0.9692660 * v[0] + 1.8760108 * v[1] + 0.0415560 * v[2],
                   0.0556434 * v[0] - 0.2040259 * v[1] + 1.0572252 * v[2]};
    };
    Rgb a = to_rgb(xyz), w = to_rgb(white);
    return {a[0] / w[0], a[1] / w[1], a[2] / w[2]};
}

} // namespace clppm::test

// The ground truth of a rough surface's multiple scattering: the random walk on a Smith
// microsurface of Heitz, Hanika, d'Eon and Dachsbacher 2016 ("Multiple-Scattering Microfacet BSDFs
// with the Smith Model"), for anisotropic GGX slopes (alpha_x along x, alpha_y along y), uniform
// heights on [-1, 1], a conductor with Schlick's Fresnel from f0 or (DielectricMicrosurface) a
// dielectric interface. Host side, double; the kernels' metal and rough glass lobes are checked
// against it (tests/multiple_scattering_test.cpp). Directions are in the local frame, z the
// normal; a walk starts going down along -wi.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "test_util.h"

namespace clppm::test {

struct Microsurface {
    double ax, ay;                                                          // GGX alpha along x and along y
    double f0;                                                              // Schlick's F0 (1: a white conductor)
    static constexpr double kOut = std::numeric_limits<double>::infinity(); // a height: the walk left

    // Heights: uniform on [-1, 1] (the paper's choice; the result does not depend on it).
    static double c1(double h) { return std::clamp(0.5 * (h + 1), 0.0, 1.0); }
    static double inv_c1(double u) { return std::clamp(2 * u - 1, -1.0, 1.0); }

    double alpha_of(D3 w) const { // the projected roughness along w's azimuth
        const double s2 = w.x * w.x + w.y * w.y;
        return s2 > 0 ? std::sqrt((w.x * w.x * ax * ax + w.y * w.y * ay * ay) / s2) : ax;
    }
    // Smith's Lambda for any direction (Eq. 18 of Heitz 2014 with the sign for w below).
    double lambda(D3 w) const {
        if (w.z > 0.9999999) return 0;
        if (w.z < -0.9999999) return -1;
        const double a = w.z / (std::sqrt(std::max(0.0, 1 - w.z * w.z)) * alpha_of(w));
        return 0.5 * (-1 + (a > 0 ? 1 : -1) * std::sqrt(1 + 1 / (a * a)));
    }
    double projected_area(D3 w) const { // (1 + Lambda(w)) cos(w)
        if (w.z > 0.9999999) return 1;
        if (w.z < -0.9999999) return 0;
        const double al = alpha_of(w);
        return 0.5 * (w.z + std::sqrt(w.z * w.z + std::max(0.0, 1 - w.z * w.z) * al * al));
    }
    double d(D3 m) const {
        if (m.z <= 0) return 0;
        const double x = m.x / ax, y = m.y / ay, q = x * x + y * y + m.z * m.z;
        return 1 / (M_PI * ax * ay * q * q);
    }
    double fresnel(double c) const { return f0 + (1 - f0) * std::pow(1 - std::clamp(c, 0.0, 1.0), 5); }

    // The normals visible from w (Heitz 2018), for w on either side of the surface.
    D3 sample_visible_normal(D3 w, double u1, double u2) const {
        const D3 vh = normalized({ax * w.x, ay * w.y, w.z});
        const double l2 = vh.x * vh.x + vh.y * vh.y;
        const D3 t1 = l2 > 0 ? D3{-vh.y / std::sqrt(l2), vh.x / std::sqrt(l2), 0} : D3{1, 0, 0};
        const D3 t2 = cross(vh, t1);
        const double r = std::sqrt(u1), phi = 2 * M_PI * u2, s = 0.5 * (1 + vh.z);
        const double p1 = r * std::cos(phi),
                     p2 = (1 - s) * std::sqrt(std::max(0.0, 1 - p1 * p1)) + s * r * std::sin(phi);
        const D3 nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::max(0.0, 1 - p1 * p1 - p2 * p2));
        return normalized({ax * nh.x, ay * nh.y, std::max(1e-12, nh.z)});
    }
    // G1 at height h for w going up (the masking of a ray leaving from h).
    double g1(D3 w, double h) const {
        if (w.z > 0.9999999) return 1;
        if (w.z <= 0) return 0;
        return std::pow(c1(h), lambda(w));
    }
    // The next height a ray along wr from height hr meets the surface, or kOut (Eq. 24 inverted).
    double next_height(D3 wr, double hr, double u) const {
        if (wr.z > 0.9999999) return kOut;
        if (wr.z < -0.9999999) return inv_c1(u * c1(hr));
        if (std::fabs(wr.z) < 1e-7) return hr;
        if (u > 1 - g1(wr, hr)) return kOut;
        return inv_c1(c1(hr) / std::pow(1 - u, 1 / lambda(wr)));
    }
    // The conductor's phase function from wi (pointing away from the facet) to wo, Fresnel included.
    double phase(D3 wi, D3 wo) const {
        const D3 s = wi + wo;
        if (dot(s, s) < 1e-30) return 0;
        const D3 h = normalized(s);
        const double c = dot(wi, h);
        if (h.z <= 0 || c <= 0) return 0;
        return fresnel(c) * 0.25 * d(h) / projected_area(wi);
    }

    // One walk's estimate of f(wi, wo) cos(wo) by next-event estimation at every vertex (the paper's
    // eval), added to single[0] (the first vertex) and multiple[0] (the rest).
    template <class Rng>
    void eval(D3 wi, D3 wo, Rng& rng, double* single, double* multiple) const {
        std::uniform_real_distribution<double> u(0, 1);
        D3 wr = wi * -1.0;
        double h = 1 + inv_c1(0.999), energy = 1;
        for (int order = 1; order <= 256; ++order) {
            h = next_height(wr, h, u(rng));
            if (h == kOut) return;
            *(order == 1 ? single : multiple) += energy * phase(wr * -1.0, wo) * g1(wo, h);
            const D3 m = sample_visible_normal(wr * -1.0, u(rng), u(rng));
            energy *= fresnel(dot(wr * -1.0, m));
            wr = wr - m * (2 * dot(wr, m));
        }
    }

    // One walk from wi to where it leaves: its direction, the energy it carries, its bounces.
    template <class Rng>
    int walk(D3 wi, Rng& rng, D3* out, double* energy) const {
        std::uniform_real_distribution<double> u(0, 1);
        D3 wr = wi * -1.0;
        double h = 1 + inv_c1(0.999);
        *energy = 1;
        for (int bounces = 0; bounces <= 256; ++bounces) {
            h = next_height(wr, h, u(rng));
            if (h == kOut) {
                *out = wr;
                return bounces;
            }
            const D3 m = sample_visible_normal(wr * -1.0, u(rng), u(rng));
            *energy *= fresnel(dot(wr * -1.0, m));
            wr = wr - m * (2 * dot(wr, m));
        }
        *energy = 0; // a walk that never leaves (measure zero) carries nothing out
        *out = wr;
        return 256;
    }
};

// The same walk on a rough dielectric interface of relative index eta (inside over outside), the
// paper's Sec. 5.3: at each facet the light reflects with the exact Fresnel reflectance and
// otherwise refracts to the other side, where the microsurface seen from below is the same one
// mirrored (heights and directions negated, eta inverted). Lossless: every walk leaves, above
// (reflected) or below (transmitted), carrying all its energy.
struct DielectricMicrosurface : Microsurface {
    double eta;
    DielectricMicrosurface(double ax_, double ay_, double eta_) : Microsurface{ax_, ay_, 1}, eta(eta_) {}

    // Fresnel's reflectance for unpolarised light from wi (pointing away) at the facet m.
    static double fresnel_dielectric(D3 wi, D3 m, double eta) {
        const double ci = dot(wi, m), ct2 = 1 - (1 - ci * ci) / (eta * eta);
        if (ct2 <= 0) return 1;
        const double ct = std::sqrt(ct2);
        const double rs = (ci - eta * ct) / (ci + eta * ct), rp = (eta * ci - ct) / (eta * ci + ct);
        return 0.5 * (rs * rs + rp * rp);
    }
    static D3 refract(D3 wi, D3 m, double eta) {
        const double ci = dot(wi, m), ct2 = 1 - (1 - ci * ci) / (eta * eta);
        return normalized(m * (ci / eta - std::sqrt(std::max(0.0, ct2))) - wi * (1 / eta));
    }

    template <class Rng>
    int walk(D3 wi, Rng& rng, D3* out) const {
        std::uniform_real_distribution<double> u(0, 1);
        D3 wr = wi * -1.0;
        double h = 1 + inv_c1(0.999);
        bool outside = true;
        for (int bounces = 0; bounces <= 256; ++bounces) {
            h = outside ? next_height(wr, h, u(rng)) : -next_height(wr * -1.0, -h, u(rng));
            if (std::isinf(h)) {
                *out = wr;
                return bounces;
            }
            const D3 w = wr * -1.0; // towards where the light came from
            const double e = outside ? eta : 1 / eta;
            const D3 m = outside ? sample_visible_normal(w, u(rng), u(rng))
                                 : sample_visible_normal(w * -1.0, u(rng), u(rng)) * -1.0;
            if (u(rng) < fresnel_dielectric(w, m, e)) {
                wr = m * (2 * dot(w, m)) - w;
            } else {
                wr = refract(w, m, e);
                outside = !outside;
            }
        }
        *out = wr;
        return 256;
    }
};

} // namespace clppm::test

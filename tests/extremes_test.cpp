// End-to-end renders at the extremes of the parameters and of the scenes (GitHub issue "Kernel
// correctness and numerical stability at the extremes"): alpha from 0.01 to 1, initial radii of a
// thousandth of a pixel and a tenth of the scene, scenes scaled by 1e-4 and 1e4, light power
// scaled by 1e-6 and 1e6, hit points no photon ever reaches, a light no surface sees, photons
// escaping an open scene, a scene of mirrors only, degenerate and needle triangles. Small
// images; every render is checked for NaN and Inf.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "scene/device_scene.h"
#include "scene/texture_sampling.h"
#include "scene_builders.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

RenderSettings small(unsigned size, uint64_t photons, DirectLighting direct, const std::string& integrator = "ppm") {
    RenderSettings s;
    s.width = s.height = size;
    s.photons = photons;
    s.direct = direct;
    s.integrator = integrator;
    s.spp = 1;
    return s;
}

const char* name(const std::string& i) { return i == "ppm" ? "PPM" : i == "sppm" ? "SPPM" : "PPPM"; }

// Renders and checks the one thing every render must satisfy.
Image render(const Scene& scene, const RenderSettings& s, uint64_t passes, IntegratorStats* stats = nullptr) {
    Image img = render_passes(scene, s, passes, stats);
    EXPECT_EQ(count_nonfinite(img), 0u) << name(s.integrator) << " produced NaN or Inf";
    return img;
}

// Mean relative deviation of a render of plane_under_point_light (scaled by `scale`) from the
// closed form over the central pixels: sum |L - L_ref| / sum L_ref; *bias gets the signed
// sum (L - L_ref) / sum L_ref.
double scaled_plane_error(const Scene& scene, const RenderSettings& s, const Image& img, double rho, double I, double h,
                          double scale, double* bias = nullptr) {
    float bmin[3] = {-4 * float(scale), 0, -4 * float(scale)}, bmax[3] = {4 * float(scale), 0, 4 * float(scale)};
    dev::Camera cam = make_camera(scene, s, bmin, bmax, nullptr);
    // The closed form is scale free once positions are in units of `scale`.
    for (int k = 0; k < 3; ++k) cam.origin[k] /= float(scale);
    const int w = img.width, m = w / 8;
    return plane_error(img, cam, m, w - m, 1, rho, I, h, bias);
}

// The same scene with every length multiplied by s: positions, camera, punctual light positions;
// point and spot intensities times s^2 so that irradiance (I / d^2) is unchanged; area light
// radiance and directional irradiance unchanged.
Scene scaled(Scene scene, double s) {
    for (Vec3& p : scene.positions) p.x *= float(s), p.y *= float(s), p.z *= float(s);
    for (CameraDesc& c : scene.cameras)
        for (float& v : c.position) v *= float(s);
    for (dev::Light& l : scene.punctual_lights) {
        for (int k = 0; k < 3; ++k) l.position[k] *= float(s);
        if (l.type == LIGHT_POINT || l.type == LIGHT_SPOT)
            for (int k = 0; k < 3; ++k) l.radiance[k] *= float(s * s);
    }
    return scene;
}

// Every light's emitted power times f.
Scene brighter(Scene scene, double f) {
    for (dev::Material& m : scene.materials)
        for (float& e : m.emission) e *= float(f);
    for (dev::Light& l : scene.punctual_lights)
        for (float& r : l.radiance) r *= float(f);
    return scene;
}

// Mean over 4 x 4 blocks of the image, for comparing renders that differ by noise.
std::vector<double> block_means(const Image& img) {
    std::vector<double> b;
    const int n = 4, bw = img.width / n, bh = img.height / n;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) b.push_back(region_mean(img, i * bw, j * bh, (i + 1) * bw, (j + 1) * bh));
    return b;
}

} // namespace

// The furnace (closed sphere, albedo 0.5, Le = 1: L = 2 everywhere) has no spatial variation, so
// every alpha converges to the same 2.0 whatever the radius does; photons only (no direct-light
// shortcut). Tolerance 1.5%, 4% for alpha = 0.01, which keeps 1% of each pass's photons: at 16
// passes of 10k photons its mean over six seeds was 1.999 with a spread of 1.92 to 2.04 (32x32,
// clppm --seed 1..6); the others stay within 0.5%.
// Radius: alpha = 1 is photon mapping with a fixed radius (mean R stays R0, to float summation:
// 1e-6); smaller alpha shrinks R faster.
TEST(Extremes, AlphaFromOneHundredthToOneConvergesOnTheFurnace) {
    for (std::string integ : {"ppm", "sppm", "pppm"}) {
        double previous_radius = 0;
        for (double alpha : {0.01, 0.5, 0.99, 1.0}) {
            if (integ != "ppm" && alpha != 0.5 && alpha != 1.0) continue; // the cheap subset
            RenderSettings s = small(16, 10000, DirectLighting::Photons, integ);
            s.alpha = alpha;
            IntegratorStats st;
            Image img = render(furnace(0.5f, 1.0f), s, 16, &st);
            EXPECT_NEAR(mean_radiance(img), 2.0, alpha == 0.01 ? 0.08 : 0.03) << name(integ) << " alpha " << alpha;
            ASSERT_GT(st.initial_radius, 0.0);
            EXPECT_TRUE(std::isfinite(st.mean_radius) && st.mean_radius > 0) << name(integ) << " alpha " << alpha;
            if (alpha == 1.0) {
                EXPECT_NEAR(st.mean_radius / st.initial_radius, 1.0, 1e-6) << name(integ) << ": alpha 1 must keep R0";
            } else {
                EXPECT_LT(st.mean_radius, st.initial_radius) << name(integ) << " alpha " << alpha;
            }
            if (integ == "ppm") {
                EXPECT_GT(st.mean_radius, previous_radius) << "R grows with alpha";
            }
            previous_radius = st.mean_radius;
        }
    }
}

// An initial radius of a thousandth of a pixel's footprint: photons (almost) never land inside,
// hit point statistics divide by tiny areas, and nothing may turn NaN or Inf. With explicit direct
// light the plane under a point light has no indirect light at all (photons leave after one
// bounce), so the image must still match the closed form (3%, as ppm_test); with photons only it
// must be finite and non-negative.
TEST(Extremes, InitialRadiusOfAThousandthOfAPixel) {
    const float rho = 0.5f, I = 10.f, h = 1.f;
    Scene scene = plane_under_point_light(rho, I, h);
    // The camera is 3 above the plane with yfov 0.6: one pixel of 16 spans 3 * 2 tan(0.3) / 16.
    const double footprint = 3 * 2 * std::tan(0.3) / 16;
    for (std::string integ : {"ppm", "sppm"}) {
        RenderSettings s = small(16, 20000, DirectLighting::Sample, integ);
        s.radius = 1e-3 * footprint;
        IntegratorStats st;
        Image img = render(scene, s, 12, &st);
        EXPECT_NEAR(st.initial_radius, s.radius, 1e-12);
        EXPECT_LT(scaled_plane_error(scene, s, img, rho, I, h, 1.0), 0.03) << name(integ);
        s.direct = DirectLighting::Photons;
        Image ph = render(scene, s, 12, &st);
        for (float v : ph.rgb) ASSERT_GE(v, 0.0f) << name(integ);
        EXPECT_TRUE(std::isfinite(st.mean_radius) && st.mean_radius > 0 && st.mean_radius <= s.radius * (1 + 1e-6));
    }
}

// An initial radius of a tenth of the scene (0.2 in the unit furnace): hugely blurred in general,
// but inside a sphere the surface within straight-line distance r of a point has area exactly
// pi r^2, so the furnace stays unbiased: 2.0 within 1.5%. On the plane under a point light the
// blur flattens the peak: finite, positive, not above the closed form's maximum.
TEST(Extremes, InitialRadiusOfATenthOfTheScene) {
    for (std::string integ : {"ppm", "sppm"}) {
        RenderSettings s = small(16, 20000, DirectLighting::Photons, integ);
        s.radius = 0.2;
        Image img = render(furnace(0.5f, 1.0f), s, 8);
        EXPECT_NEAR(mean_radiance(img), 2.0, 0.03) << name(integ);

        Scene plane = plane_under_point_light(0.5f, 10.f, 1.f);
        s.radius = 0.1 * 2 * std::sqrt(4.0 * 4 + 4 * 4 + 0.25); // a tenth of the bounding sphere's diameter
        Image blur = render(plane, s, 8);
        const double peak = 0.5 / M_PI * 10.0; // rho / pi * I / h^2 right below the light
        double lo = 1e30, hi = 0;
        for (float v : blur.rgb) lo = std::min(lo, double(v)), hi = std::max(hi, double(v));
        EXPECT_GT(lo, 0.0) << name(integ) << ": every pixel sees the lit plane";
        EXPECT_LT(hi, 1.05 * peak) << name(integ);
    }
}

// The same scenes at 1e-4 and 1e4 times their size (point light intensity times s^2) give the
// same image: the plane under a point light against its closed form at every scale (PPM and
// SPPM, explicit direct light and photons only), and the closed box against its unscaled render
// (4 x 4 block means within 3%: same seed, so the noise is largely shared).
TEST(Extremes, SceneScaledBy1eMinus4And1e4RendersTheSame) {
    const float rho = 0.5f, I = 10.f, h = 1.f;
    for (double scale : {1e-4, 1.0, 1e4})
        for (std::string integ : {"ppm", "sppm"})
            for (DirectLighting direct : {DirectLighting::Sample, DirectLighting::Photons}) {
                Scene scene = scaled(plane_under_point_light(rho, I, h), scale);
                RenderSettings s = small(16, 50000, direct, integ);
                Image img = render(scene, s, 8);
                // 4%: 16 passes of 50k photons put photons-only PPM within 2-3% (ppm_test uses 3%
                // at 24 passes of 100k); sampled direct light is within 1%.
                EXPECT_LT(scaled_plane_error(scene, s, img, rho, I, h, scale), 0.04)
                    << "scale " << scale << " " << name(integ)
                    << (direct == DirectLighting::Sample ? " sample" : " photons");
            }
    RenderSettings s = small(16, 20000, DirectLighting::Sample);
    IntegratorStats st1;
    Image ref = render(diffuse_box(), s, 4, &st1);
    for (double scale : {1e-4, 1e4}) {
        IntegratorStats st;
        Image img = render(scaled(diffuse_box(), scale), s, 4, &st);
        EXPECT_NEAR(st.initial_radius / (st1.initial_radius * scale), 1.0, 1e-3) << "scale " << scale;
        EXPECT_EQ(st.hitpoints, st1.hitpoints) << "scale " << scale;
        // The same random numbers make the same decisions at any scale, so pixels agree to float
        // rounding, except where a decision sits on a knife edge: a pixel-centre ray through an
        // edge of the box (pixels (2,2) and (13,13) graze the wall/ceiling edges) may hit either
        // face. Such a hit point lies on the edge itself, where the gather disc's coverage
        // (kernels/disc_coverage.cl) sends probe rays along the other face's plane, another knife
        // edge: the corner pixels (0,0), (15,0), (1,1), (14,1), (0,15), (15,15) join (2,2) and
        // (13,13). So: the median pixel within 1e-3, and at most 10 of 256 pixels off by more than 2%.
        std::vector<double> dev;
        for (size_t i = 1; i < img.rgb.size(); i += 3) dev.push_back(std::fabs(img.rgb[i] / ref.rgb[i] - 1));
        std::sort(dev.begin(), dev.end());
        EXPECT_LT(dev[dev.size() / 2], 1e-3) << "scale " << scale << ": median pixel deviation";
        size_t off = 0;
        for (double d : dev) off += !(d <= 0.02);
        EXPECT_LE(off, 10u) << "scale " << scale << ": pixels that differ by more than 2%";
    }
}

// Light power times 1e-9 to 1e9 scales the image by exactly that: photon flux is carried in units
// of the total power, so the same random numbers trace the same paths and only the final scale
// changes. Per pixel within 1e-4 relative (float flux and radiance, rounded a few times) of the
// unscaled image times the factor, plus 1e-6 of the image's mean for near-black pixels.
TEST(Extremes, LightPowerScalesTheImageLinearly) {
    struct Case {
        Scene scene;
        DirectLighting direct;
    };
    std::vector<Case> cases = {{diffuse_box(false), DirectLighting::Sample},
                               {plane_under_point_light(0.5f, 10.f, 1.f), DirectLighting::Photons}};
    for (std::string integ : {"ppm", "sppm"})
        for (const Case& c : cases) {
            RenderSettings s = small(16, 10000, c.direct, integ);
            Image base = render(c.scene, s, 3);
            const double mean = mean_radiance(base);
            ASSERT_GT(mean, 0.0);
            for (double f : {1e-9, 1e-6, 1e6, 1e9}) {
                Image img = render(brighter(c.scene, f), s, 3);
                EXPECT_EQ(count_nonfinite(img), 0u) << name(integ) << " factor " << f;
                EXPECT_EQ(count_negative(img), 0u) << name(integ) << " factor " << f;
                double worst = 0;
                for (size_t i = 0; i < img.rgb.size(); ++i) {
                    double want = f * base.rgb[i];
                    worst = std::max(worst, std::fabs(img.rgb[i] - want) / (1e-4 * std::fabs(want) + 1e-6 * f * mean));
                }
                EXPECT_LE(worst, 1.0) << name(integ) << " factor " << f << ": error in units of the tolerance";
            }
        }
}

// Hit points that no photon reaches for two thousand passes: the only light is a spot below a
// plane, pointing away from it, so no surface sees the light and every photon escapes. The image
// stays exactly zero, R stays R0 (no photon, no update: Eq. 7 with M = 0), nothing is stored.
TEST(Extremes, HitPointsNoPhotonReachesStayZeroForThousandsOfPasses) {
    Scene s;
    s.source = "<unlit plane>";
    uint32_t m = add_material(s, 0.8f, 0.8f, 0.8f);
    add_quad(s, {-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, m);
    add_spot_light(s, {0, -0.5f, 0}, 100.f, 0.4f, 0.6f); // points straight down, away from the plane
    add_camera(s, {0, 2, 0}, {0, -1, 0}, {0, 0, -1}, 0.8f);
    for (std::string integ : {"ppm", "sppm"}) {
        RenderSettings rs = small(4, 256, DirectLighting::Sample, integ);
        IntegratorStats st;
        Image img = render(s, rs, integ == "ppm" ? 2000 : 200, &st);
        for (float v : img.rgb) ASSERT_EQ(v, 0.0f) << name(integ);
        EXPECT_EQ(st.photons_stored, 0u) << name(integ);
        EXPECT_NEAR(st.mean_radius / st.initial_radius, 1.0, 1e-6) << name(integ) << ": R changed without photons";
    }
}

// A light no surface sees, beside one that lights the plane: the spot below the plane takes its
// share of photons (by power, 16%) and of light samples, which all come to nothing; the image
// must still be the point light's closed form (pick probabilities and total power cancel).
// Sampled direct light (photons then carry nothing here: no indirect light on a lone plane):
// 32 passes, each hit point's estimate is I / (d^2 pick) on 84% of its samples and 0 otherwise,
// a per-pixel relative noise of sqrt(0.16/0.84/32) = 7.7%: the signed bias over the 144 central
// pixels must stay below 3% (5 sigma of their mean) and the mean absolute error below 10%.
// Photons only: as in the scaling test, mean absolute error below 5%.
TEST(Extremes, ALightNoSurfaceSeesChangesNothing) {
    const float rho = 0.5f, I = 10.f, h = 1.f;
    Scene scene = plane_under_point_light(rho, I, h);
    add_spot_light(scene, {0, -0.5f, 0}, 3 * I, 0.4f, 0.6f); // below the plane, pointing down
    for (std::string integ : {"ppm", "sppm"})
        for (DirectLighting direct : {DirectLighting::Sample, DirectLighting::Photons}) {
            const bool sample = direct == DirectLighting::Sample;
            RenderSettings s = small(16, sample ? 5000 : 50000, direct, integ);
            Image img = render(scene, s, sample ? 32 : 8);
            double bias = 0, err = scaled_plane_error(scene, s, img, rho, I, h, 1.0, &bias);
            std::string what = std::string(name(integ)) + (sample ? " sample" : " photons");
            EXPECT_LT(err, sample ? 0.10 : 0.05) << what;
            EXPECT_LT(std::fabs(bias), sample ? 0.03 : 0.03) << what;
        }
}

// An open scene: a lit plane seen towards its horizon, so the upper image rows look into empty
// space and most photons escape. Sky pixels are exactly zero (no hit point, no emission), plane
// pixels positive and finite.
TEST(Extremes, PhotonsEscapingAnOpenSceneLeaveTheSkyBlack) {
    Scene scene = plane_under_point_light(0.5f, 10.f, 1.f);
    scene.cameras.clear();
    add_camera(scene, {0, 0.5f, 3.5f}, {0, 0, -1}, {0, 1, 0}, 0.9f); // horizon at mid-image, far edge at z = -4
    for (std::string integ : {"ppm", "sppm"}) {
        RenderSettings s = small(16, 20000, DirectLighting::Sample, integ);
        Image img = render(scene, s, 4);
        for (int y = 0; y < 6; ++y)
            for (int x = 0; x < 16; ++x)
                for (int c = 0; c < 3; ++c)
                    ASSERT_EQ(img.rgb[3 * (y * 16 + x) + c], 0.0f) << name(integ) << " sky pixel " << x << "," << y;
        EXPECT_GT(region_mean(img, 4, 12, 12, 16), 0.0) << name(integ) << ": the plane is lit";
    }
}

// Only specular surfaces: a closed mirror box with a glass sphere inside and a mirror that also
// emits. PPM finds no hit point at all and stores no photon; the renderer must not crash and the
// image (emission seen along specular chains) must be finite and positive.
TEST(Extremes, ASceneOfOnlySpecularSurfaces) {
    Scene s;
    s.source = "<mirror box>";
    uint32_t mirror = add_material(s, 0.9f, 0.9f, 0.9f, 0.f, false, MAT_MIRROR);
    uint32_t glass = add_material(s, 1, 1, 1, 0.f, false, MAT_GLASS, 1.5f);
    uint32_t lamp = add_material(s, 0.9f, 0.9f, 0.9f, 5.f, false, MAT_MIRROR);
    add_quad(s, {-1, -1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, -1, -1}, mirror);
    add_quad(s, {-1, 1, -1}, {1, 1, -1}, {1, 1, 1}, {-1, 1, 1}, mirror);
    add_quad(s, {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, mirror);
    add_quad(s, {-1, -1, 1}, {-1, 1, 1}, {1, 1, 1}, {1, -1, 1}, mirror);
    add_quad(s, {-1, -1, -1}, {-1, 1, -1}, {-1, 1, 1}, {-1, -1, 1}, mirror);
    add_quad(s, {1, -1, -1}, {1, -1, 1}, {1, 1, 1}, {1, 1, -1}, mirror);
    add_quad(s, {-0.3f, 0.99f, -0.3f}, {0.3f, 0.99f, -0.3f}, {0.3f, 0.99f, 0.3f}, {-0.3f, 0.99f, 0.3f}, lamp);
    add_sphere(s, {0.2f, -0.5f, -0.2f}, 0.4f, 8, 16, glass);
    add_camera(s, {0, 0, 0.95f}, {0, 0, -1}, {0, 1, 0}, 1.3f);
    for (std::string integ : {"ppm", "sppm"})
        for (DirectLighting direct : {DirectLighting::Sample, DirectLighting::Photons}) {
            IntegratorStats st;
            Image img = render(s, small(16, 5000, direct, integ), 3, &st);
            EXPECT_EQ(st.photons_stored, 0u) << name(integ);
            if (integ == "ppm") {
                EXPECT_EQ(st.hitpoints, 0u);
            }
            EXPECT_GT(mean_radiance(img), 0.0) << name(integ) << ": the lamp is seen in the mirrors";
        }
}

// Degenerate triangles (a point, a line) and needles (length 1.5, width 1e-7), diffuse and
// emissive, inside the diffuse box: the BVH, intersection, light setup (zero-area emitters are
// no lights) and emission must cope. Images finite, and within 10% of the box without them (4 x 4
// blocks; the needles cover almost nothing; the added lights decorrelate the two renders' noise,
// which reached 8.3% in the worst block over seeds 2 to 6 at 4 passes: 16 passes halve it).
TEST(Extremes, DegenerateAndNeedleTrianglesRenderFinite) {
    Scene box = diffuse_box(false);
    // Off the box's axis: from its centre the box's edges pass exactly through pixel centres, where
    // PPM's one eye ray per pixel ties between two walls, and which wall wins depends on the BVH's
    // layout, which the added triangles change (a whole pixel flips between white and red).
    box.cameras[0].position[0] += 0.0123f;
    box.cameras[0].position[1] += 0.0071f;
    Scene odd = box;
    uint32_t white = 0, glow = add_material(odd, 0.5f, 0.5f, 0.5f, 20.f, true);
    Vec3 p{0.1f, -0.2f, 0.1f};
    for (uint32_t m : {white, glow}) {
        add_triangle(odd, p, p, p, m);                                                               // a point
        add_triangle(odd, {-0.5f, 0, 0}, {0, 0, 0}, {0.5f, 0, 0}, m);                                // a line
        add_triangle(odd, {-0.7f, -0.9f, -0.5f}, {0.8f, 0.5f, -0.5f}, {0.8f, 0.5f, -0.4999999f}, m); // needle
        add_triangle(odd, {0.3f, -0.9f, 0.2f}, {0.3f, 0.6f, 0.2f}, {0.3000001f, 0.6f, 0.2f}, m);     // needle
        p.x += 0.2f;
    }
    for (std::string integ : {"ppm", "sppm"}) {
        RenderSettings s = small(16, 20000, DirectLighting::Sample, integ);
        std::vector<double> ref = block_means(render(box, s, 16));
        std::vector<double> b = block_means(render(odd, s, 16));
        for (size_t i = 0; i < b.size(); ++i) EXPECT_NEAR(b[i] / ref[i], 1.0, 0.1) << name(integ) << " block " << i;
    }
}

// Texture coordinates anywhere a float reaches (3e38, mixes of +-1e30 and 1e38, whose
// interpolation overflows) look up texels in range: the image stays finite and non-negative, for
// repeat and clamp-to-edge alike. They used to render NaN and pixels down to -5e7.
TEST(Extremes, HugeTextureCoordinatesStayFinite) {
    for (uint32_t wrap : {0u, 3u}) {
        Scene scene = plane_under_point_light(0.8f, 10.f, 1.f);
        scene.textures.push_back(plain_texture(0, 2, 2, wrap));
        for (float v : {0.2f, 0.9f, 0.5f, 1.0f}) scene.texels.push_back({v, v, v, 1.f});
        for (dev::Material& m : scene.materials) m.base_color_tex = 0;
        const float coords[][6] = {{3e38f, 3e38f, -3e38f, 3e38f, 3e38f, -3e38f},
                                   {1e30f, -1e30f, 1e38f, 1e38f, -1e30f, 1e38f}};
        for (size_t t = 0; t < scene.shading.size(); ++t) {
            dev::TriShading& sh = scene.shading[t];
            const float* c = coords[t % 2];
            sh.uv0[0] = c[0], sh.uv0[1] = c[1], sh.uv1[0] = c[2], sh.uv1[1] = c[3], sh.uv2[0] = c[4], sh.uv2[1] = c[5];
        }
        for (std::string integ : {"ppm", "sppm"}) {
            Image img = render(scene, small(16, 5000, DirectLighting::Sample, integ), 2);
            EXPECT_EQ(count_nonfinite(img), 0u) << name(integ) << " wrap " << wrap;
            EXPECT_EQ(count_negative(img), 0u) << name(integ) << " wrap " << wrap;
            EXPECT_GT(mean_radiance(img), 0.0) << name(integ) << " wrap " << wrap;
        }
    }
}

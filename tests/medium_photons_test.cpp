// Photons in participating media: PPM, SPPM and PPPM store photons where their free flights collide
// (kernels/photon_trace.cl), make volume hit points where the eye paths' do (kernels/eye_pass.cl),
// gather them within a sphere (kernels/gather.cl) and add each pass's estimate to the pixel
// (kernels/sppm.cl volume_accumulate), with explicit direct light at the volume hit points (a
// light sample and a phase sample under MIS, kernels/direct_light.cl); with --volume-gather beams
// each pixel's first scattering segment gathers them along its length instead (kernels/beam.cl).
// Held to the closed forms the path tracer is held to
// (medium_test.cpp), and to the path tracer where there is none:
// - the scattering furnace (walls glowing 1, albedo 0.5, a medium that absorbs nothing: radiance 2
//   everywhere), in the world's medium (volume hit points, and --volume-gather beams) and in a
//   closed mesh's;
// - single scattering from a point light against the host quadrature, by light samples at the
//   volume hit points (--direct sample) and by the photons themselves (--direct photons);
// - PPM's fixed volume hit points, with statistics of their own, in the furnace;
// - fog inside a glass cube inside fog, in the furnace, for every integrator that renders media;
// - the translucent block (tests/data/wax_block.gltf: diffuse transmission into a scattering
//   volume) against the path tracer's mean;
// - a render stopped and resumed equals one never stopped.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "medium_scenes.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

RenderSettings photon_settings(const char* integrator, unsigned size, unsigned max_bounces, uint64_t photons) {
    RenderSettings s = pt_settings(size, max_bounces);
    s.integrator = integrator;
    s.photons = photons;
    return s;
}

} // namespace

TEST(MediumPhotons, ScatteringFurnaceKeepsItsRadiance) {
    for (const bool beams : {true, false}) {
        for (const char* integrator : {"sppm", "pppm"}) {
            SCOPED_TRACE(std::string(integrator) + (beams ? ", --volume-gather beams" : ", points"));
            Scene scene = glowing_box(0.5f, 1.f);
            set_medium(scene, {0.5f, 1.f, 2.f}, {1.f, 1.f, 1.f}, 0.6f);
            IntegratorStats stats;
            RenderSettings s = photon_settings(integrator, 16, 1024, 20000);
            s.volume_gather = beams ? VolumeGather::Beams : VolumeGather::Points;
            const Image img = render_passes(scene, s, 64, &stats);
            expect_clean(img);
            EXPECT_EQ(stats.phase_seconds.count("beam_gather"), beams ? 1u : 0u) << "beams gathered or not";
            EXPECT_GT(stats.initial_volume_radius, 0.0);
            EXPECT_LT(stats.volume_radius, stats.initial_volume_radius) << "the volume radius shrinks";
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(region_mean(img, 0, 0, 16, 16, c), 2.0, 0.04) << "channel " << c;
        }
    }
}

// PPM's volume hit points are fixed, each with statistics of its own whose sphere shrinks in 3-D
// (kernels/ppm_update.cl): the furnace's radiance from every one of them, and a radius that shrinks.
// Their weights are frozen too (the chromatic medium's spectral MIS: each is 1 only on average), so
// the mean over pixels has the noise of its samples whatever the passes: 16 a pixel hold it within
// 1.1% (2 a pixel: 2.7% in the densest channel at 16, 64 and 256 passes alike).
TEST(MediumPhotons, PpmsFixedVolumeHitPointsKeepTheFurnacesRadiance) {
    Scene scene = glowing_box(0.5f, 1.f);
    set_medium(scene, {0.5f, 1.f, 2.f}, {1.f, 1.f, 1.f}, 0.6f);
    IntegratorStats stats;
    RenderSettings s = photon_settings("ppm", 16, 1024, 20000);
    s.spp = 16;
    const Image img = render_passes(scene, s, 64, &stats);
    expect_clean(img);
    EXPECT_GT(stats.initial_volume_radius, 0.0);
    EXPECT_LT(stats.mean_radius, stats.initial_volume_radius) << "the spheres shrink";
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(region_mean(img, 0, 0, 16, 16, c), 2.0, 0.04) << "channel " << c;
}

TEST(MediumPhotons, ScatteringMeshKeepsTheFurnacesRadiance) {
    const Image img = render_passes(scattering_cube(0.5f, {0.5f, 1.f, 2.f}, {1.f, 1.f, 1.f}, 0.4f),
                                    photon_settings("sppm", 16, 1024, 20000), 64);
    expect_clean(img);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(region_mean(img, 0, 0, 16, 16, c), 2.0, 0.05) << "channel " << c;
}

// Fog inside glass inside fog: a smooth glass cube of ior 1.5 that holds a white medium of its own,
// in the world's white medium of other densities, in the glowing box. Lossless everywhere, so the
// furnace's radiance 2 is what every integrator must see through the cube's refracting faces (a
// segment's medium told by the surface it ends on, kernels/medium.cl). Photons stay in the medium
// they were stored in (Medium.id): gathered across the faces, the cube's (2.25 times as bright
// inside the glass, n^2) made the fog glow, 2.08 in the red channel by SPPM and 2.13 by PPM at
// 64 x 64. Kept apart, a sphere that reaches past the medium's boundary finds no photons in that
// part, as a disc at a surface's edge does: low by a bias that falls with the radius (SPPM 1.80 at
// 32 x 32, 1.93 at 64 x 64; PPM, whose radii shrink only where photons fall, 1.72 and 1.87).
TEST(MediumPhotons, FogInsideGlassInFogKeepsTheFurnacesRadiance) {
    Scene scene = glowing_box(0.5f, 1.f);
    set_medium(scene, {0.5f, 1.f, 2.f}, {1.f, 1.f, 1.f}, 0.3f);
    const uint32_t m = add_material(scene, 1, 1, 1, 0, false, MAT_GLASS, 1.5f, 0.f);
    dev::Material& glass = scene.materials[m];
    glass.flags |= MATERIAL_FLAG_ENCLOSES_VOLUME;
    const std::array<float, 3> inside{2.f, 1.f, 0.5f};
    for (int k = 0; k < 3; ++k) glass.attenuation[k] = inside[size_t(k)], glass.scatter[k] = 1.f;
    glass.scatter[3] = -0.2f;
    add_box(scene, {0.f, 0.f, -0.5f}, 0.4f, m, false);
    struct Case {
        const char* integrator;
        unsigned size;
        uint64_t passes;
        unsigned spp;
        double below; // the boundary's bias allowed
    };
    for (const Case& k : {Case{"pt", 16, 512, 1, 0.03}, Case{"sppm", 64, 64, 1, 0.1}, Case{"pppm", 64, 64, 1, 0.1},
                          Case{"ppm", 64, 64, 4, 0.15}}) {
        SCOPED_TRACE(k.integrator);
        RenderSettings s = photon_settings(k.integrator, k.size, 1024, 20000);
        s.spp = k.spp;
        const Image img = render_passes(scene, s, k.passes);
        expect_clean(img);
        const int n = int(k.size), q = n / 4;
        for (int c = 0; c < 3; ++c) {
            const double whole = region_mean(img, 0, 0, n, n, c), cube = region_mean(img, q, q, n - q, n - q, c);
            EXPECT_LT(whole, 2.03) << "channel " << c << ": the cube's light leaks into the fog";
            EXPECT_LT(cube, 2.03) << "channel " << c << ", through the cube";
            EXPECT_GT(whole, 2.0 - k.below) << "channel " << c;
            EXPECT_GT(cube, 2.0 - k.below) << "channel " << c << ", through the cube";
        }
    }
}

// medium_test.cpp's SingleScatteringFromAPointLight with one bounce: the volume hit points' light
// samples, or (--direct photons) the photons' first collisions gathered in spheres. Those blur the
// light's 1/r^2 glow upwards (a ball's mean of 1/r^2 exceeds its centre's): at 256 passes by 24%
// with alpha 0.7 and by 7% with alpha 0.3, which shrinks the radius faster (24 x 24 pixels make
// wide footprints, and the radius starts from them). The bias falls with the radius; the furnace
// above, whose density is uniform, has none.
TEST(MediumPhotons, SingleScatteringFromAPointLight) {
    const PointLightInFog fog;
    const Scene scene = fog.scene();
    struct Case {
        DirectLighting direct;
        double alpha, tol;
        const char* what;
    };
    double excess_07 = 0;
    for (const Case& k : {Case{DirectLighting::Sample, 0.7, 0.03, "--direct sample"},
                          Case{DirectLighting::Photons, 0.7, 0.3, "--direct photons, alpha 0.7"},
                          Case{DirectLighting::Photons, 0.3, 0.1, "--direct photons, alpha 0.3"}}) {
        SCOPED_TRACE(k.what);
        RenderSettings s = photon_settings("sppm", 24, 1, 50000);
        s.direct = k.direct;
        s.alpha = k.alpha;
        const Image img = render_passes(scene, s, 256);
        expect_clean(img);
        const dev::Camera cam = camera_of(scene, s);
        double excess = 0;
        for (int c = 0; c < 3; ++c) {
            excess += expect_region(img, cam, 0, 24, c, k.tol, fog.reference(c), "the whole image") - 1.0;
        }
        if (k.direct == DirectLighting::Photons && k.alpha == 0.7) excess_07 = excess;
        if (k.alpha == 0.3) {
            EXPECT_LT(std::fabs(excess), std::fabs(excess_07)) << "the blur shrinks with the radius";
        }
    }
}

// No closed form: the means of the path tracer's images, at equal pixels.
TEST(MediumPhotons, TranslucentBlockMatchesThePathTracer) {
    for (const char* file : {"wax_block.gltf"}) {
        SCOPED_TRACE(file);
        const std::array<double, 3> pt = render_test_scene_channels(file, "pt", 256);
        for (const char* integrator : {"sppm", "pppm", "ppm"}) {
            SCOPED_TRACE(integrator);
            const std::array<double, 3> m = render_test_scene_channels(file, integrator, 64);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(m[size_t(c)], pt[size_t(c)], 0.03 * pt[size_t(c)]) << "channel " << c;
        }
    }
}

// A checkpoint keeps the volume radius's state: a resumed render in fog is the same bit for bit.
TEST(MediumPhotons, ResumedEqualsNeverStopped) {
    for (const char* integrator : {"sppm", "pppm", "ppm"})
        expect_resume_is_exact(std::string(CLPPM_TEST_DATA) +
                                   "/fog_room.gltf --width 24 --height 24 --photons 4000 "
                                   "--quiet --no-png --integrator " +
                                   integrator,
                               integrator);
}

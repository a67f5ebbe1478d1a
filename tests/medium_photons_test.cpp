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

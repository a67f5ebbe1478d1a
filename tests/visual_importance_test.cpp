// Visual importance for photons (--visual-importance; kernels/photon_chain.cl, Hachisuka and Jensen
// 2009): the cells the hit points mark against a host reference, and never a photon dropped that a
// gather would count; the chains' image agrees with independent photons' where few paths are
// visible (a skylit room) and where half are (two rooms and a doorway), with no darkening; the
// chains find their states and adapt their steps; resume is exact; and what it cannot do is
// refused by name.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "device/kernel_launch.h"
#include "device/kernel_program.h"
#include "integrators/integrator_table.h"
#include "io/image_io.h"
#include "scene/gltf/gltf_load.h"
#include "shared_types.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

// kernels/hash_grid.cl's grid_cell and grid_bucket, on the host.
struct HostGrid {
    float origin[3];
    float inv_cell;
    uint32_t table_size;
    std::array<int, 3> cell(const float p[3]) const {
        std::array<int, 3> c{};
        for (int k = 0; k < 3; ++k)
            c[size_t(k)] = int(std::clamp(std::floor((p[k] - origin[k]) * inv_cell), -1048576.0f, 1048576.0f));
        return c;
    }
    uint32_t bucket(const std::array<int, 3>& c) const {
        const uint32_t h = (uint32_t(c[0]) * 73856093u) ^ (uint32_t(c[1]) * 19349663u) ^ (uint32_t(c[2]) * 83492791u);
        return h & (table_size - 1u);
    }
};

const char* kSkylight = CLPPM_SCENES_DIR "/skylight.gltf";
const char* kDoorway = CLPPM_SCENES_DIR "/doorway.gltf";

RenderSettings sppm(unsigned size, uint64_t photons, bool chains) {
    RenderSettings s;
    s.integrator = "sppm";
    s.width = s.height = size;
    s.photons = photons;
    s.visual_importance = chains;
    return s;
}

} // namespace

// Hit points with radii below, at and above the cell's side, some on cell faces, one unused: the
// kernel marks exactly the buckets of the cells each sphere's box overlaps (host reference), and
// every photon within a hit point's radius lies in a marked bucket.
TEST(VisualImportance, MarksTheCellsHitPointsMayGatherFrom) {
    KernelHarness h(assemble_kernel_source("visibility_mark.cl"));
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.f, 1.f), u01(0.f, 1.f);
    const float cell = 0.1f;
    HostGrid g{{-1.25f, -1.25f, -1.25f}, 1.f / cell, 4096};
    std::vector<dev::HitPoint> hps;
    std::vector<dev::HitStats> stats;
    for (int i = 0; i < 200; ++i) {
        dev::HitPoint hp{};
        for (int k = 0; k < 3; ++k) hp.pos[k] = u(rng);
        if (i % 7 == 0) hp.pos[0] = -1.25f + cell * std::round((hp.pos[0] + 1.25f) / cell); // on a cell face
        hp.pixel = i == 5 ? HITPOINT_NONE : uint32_t(i);
        const float r = cell * (i % 3 == 0 ? 0.3f : i % 3 == 1 ? 1.0f : 2.2f);
        dev::HitStats st{};
        st.r2 = double(r) * double(r);
        hps.push_back(hp);
        stats.push_back(st);
    }
    dev::GridInfo gi{};
    for (int k = 0; k < 3; ++k) gi.origin[k] = g.origin[k];
    gi.inv_cell = g.inv_cell;
    gi.table_size = g.table_size;
    gi.num_photons = uint32_t(hps.size());
    cl::Buffer gbuf = h.input(std::vector<dev::GridInfo>{gi}), hbuf = h.input(hps), sbuf = h.input(stats);
    std::vector<unsigned char> zeros(g.table_size, 0);
    cl::Buffer seen(h.dc.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, zeros.size(), zeros.data());
    cl::Kernel mark(h.program, "visibility_mark");
    set_args(mark, 0, gbuf, hbuf, sbuf, cl_uint(hps.size()), cl_float(0.f), seen);
    h.run(mark, hps.size());
    std::vector<unsigned char> marked = h.read<unsigned char>(seen, g.table_size);

    std::set<uint32_t> expected;
    for (size_t i = 0; i < hps.size(); ++i) {
        if (hps[i].pixel == HITPOINT_NONE) continue;
        const float r = std::sqrt(float(stats[i].r2)) * 1.001f;
        float lo_p[3], hi_p[3];
        for (int k = 0; k < 3; ++k) lo_p[k] = hps[i].pos[k] - r, hi_p[k] = hps[i].pos[k] + r;
        auto lo = g.cell(lo_p), hi = g.cell(hi_p);
        for (int z = lo[2]; z <= hi[2]; ++z)
            for (int y = lo[1]; y <= hi[1]; ++y)
                for (int x = lo[0]; x <= hi[0]; ++x) expected.insert(g.bucket({x, y, z}));
    }
    size_t n_marked = 0;
    for (uint32_t b = 0; b < g.table_size; ++b) {
        EXPECT_EQ(marked[b] != 0, expected.count(b) == 1) << "bucket " << b;
        n_marked += marked[b] != 0;
    }
    EXPECT_GT(n_marked, 300u);
    EXPECT_LT(n_marked, size_t(g.table_size)); // not everything: the test can fail

    // Photons within R of a hit point, many right at the sphere's surface: their buckets are marked.
    for (size_t i = 0; i < hps.size(); ++i) {
        if (hps[i].pixel == HITPOINT_NONE) continue;
        const float r = std::sqrt(float(stats[i].r2));
        for (int j = 0; j < 200; ++j) {
            float d[3] = {u(rng), u(rng), u(rng)};
            const float l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            const float t = j % 2 ? 1.0f : u01(rng);
            float p[3];
            for (int k = 0; k < 3; ++k) p[k] = hps[i].pos[k] + d[k] / l * r * t;
            ASSERT_NE(marked[g.bucket(g.cell(p))], 0) << "photon near hit point " << i << " dropped";
        }
    }
}

// The error estimate with chains. The passes' estimates must average to the film's image: with
// the photon power of independent photons they came out over 100 times too bright, as the chains
// deposit many states per uniform path. The estimated visible fraction, one factor for the whole
// image, adds its relative variance 1 / V_c to every pixel's.
TEST(VisualImportance, ErrorEstimateDescribesTheChainsImage) {
    for (const char* name : {"sppm", "ppm"}) {
        RenderSettings s = sppm(24, 40000, true);
        s.integrator = name;
        s.spp = 1;
        DeviceContext dc(test_device());
        Scene scene = load_gltf(kSkylight);
        DeviceScene ds = upload_scene(dc, scene, s);
        cl::Program program =
            build_program(dc, integrator_row(s.integrator).program_file, integrator_build_options(s, dc.info));
        std::unique_ptr<IntegratorBase> integ = make_integrator(dc, ds, s, program);
        integ->enable_error_estimation();
        integ->prepare();
        for (int p = 0; p < 48; ++p) integ->run_pass();
        const Image img = integ->image();
        const ErrorImage e = integ->error_estimate(0.95);
        double image_y = 0, stats_y = 0;
        for (size_t i = 0; i < e.luminance.size(); ++i) {
            image_y += 0.2126 * img.rgb[3 * i] + 0.7152 * img.rgb[3 * i + 1] + 0.0722 * img.rgb[3 * i + 2];
            stats_y += e.luminance[i];
        }
        EXPECT_NEAR(stats_y / image_y, 1.0, 0.03) << name;
        const double v = integ->normalization_variance();
        EXPECT_GT(v, 0) << name;
        EXPECT_LT(v, 1e-3) << name << ": fewer than 1000 visible uniform paths";
        for (size_t i = 0; i < e.sigma.size(); ++i)
            ASSERT_GE(double(e.sigma[i]), 0.999 * std::sqrt(v) * e.luminance[i]) << name << " pixel " << i;
        EXPECT_TRUE(std::isfinite(e.expected_error)) << name;
        std::printf("%s: passes' mean / image %.4f, 1 / V_c %.2e, estimated error %.4f\n", name, stats_y / image_y, v,
                    e.expected_error);
    }
}

// A room lit by the sun through a skylight: about one path in 150 enters. The chains deposit a
// state almost every step, adapt their mutations towards an acceptance of 0.234, store many times
// the photons, and give the image independent photons give (the same radii: the same bias).
TEST(VisualImportance, SkylitRoomAgreesWithIndependentPhotonsAndStoresManyMore) {
    IntegratorStats plain_stats, chain_stats;
    RenderSettings s = sppm(24, 40000, false);
    s.radius = 0.06;
    Image plain = render_passes(load_gltf(kSkylight), s, 96, &plain_stats);
    s.visual_importance = true;
    Image chains = render_passes(load_gltf(kSkylight), s, 96, &chain_stats);
    ASSERT_EQ(count_nonfinite(chains), 0u);
    ASSERT_EQ(count_negative(chains), 0u);

    const uint64_t* c = chain_stats.chain_counts;
    const double uniform_paths = double(chain_stats.photons_emitted);
    EXPECT_LT(c[CHAIN_UNIFORM_VISIBLE] / uniform_paths, 0.02);
    EXPECT_GT(c[CHAIN_UNIFORM_VISIBLE], 1000u);
    EXPECT_GT(c[CHAIN_STATES] / uniform_paths, 0.8) << "chains that never find a state";
    const double acceptance = double(c[CHAIN_ACCEPTED]) / double(c[CHAIN_MUTATIONS]);
    EXPECT_GT(acceptance, 0.12);
    EXPECT_LT(acceptance, 0.40);
    EXPECT_GT(chain_stats.photons_stored, 10 * plain_stats.photons_stored);

    EXPECT_NEAR(mean_radiance(chains) / mean_radiance(plain), 1.0, 0.03);
    const int half = plain.width / 2;
    for (int q = 0; q < 4; ++q) {
        const int x0 = (q & 1) * half, y0 = (q >> 1) * half;
        EXPECT_NEAR(region_mean(chains, x0, y0, x0 + half, y0 + half) /
                        region_mean(plain, x0, y0, x0 + half, y0 + half),
                    1.0, 0.08)
            << "quadrant " << q;
    }
}

// Two rooms and a doorway: about half the uniform paths are visible, so most steps swap in a
// uniform path and a mutation's proposal must not reuse the rejected one's numbers. When it did
// (the tail of the invisible uniform path), the chains drifted towards invisible states and this
// image came out 2% dark.
TEST(VisualImportance, DoorwayMeanIsNotDarkened) {
    RenderSettings s = sppm(32, 50000, false);
    s.radius = 0.05;
    Image plain = render_passes(load_gltf(kDoorway), s, 48);
    s.visual_importance = true;
    IntegratorStats st;
    Image chains = render_passes(load_gltf(kDoorway), s, 48, &st);
    const double visible = double(st.chain_counts[CHAIN_UNIFORM_VISIBLE]) / double(st.photons_emitted);
    EXPECT_GT(visible, 0.2);
    EXPECT_LT(visible, 0.8);
    EXPECT_NEAR(mean_radiance(chains) / mean_radiance(plain), 1.0, 0.007);
}

TEST(VisualImportance, StoppedAndResumedEqualsNeverStopped) {
    for (const char* integrator : {"sppm", "ppm"}) {
        const std::string a = std::string(" ") + kSkylight + " --width 20 --height 20 --photons 3000 --quiet --no-png" +
                              " --visual-importance --integrator " + integrator;
        const std::string d = expect_resume_is_exact(a, integrator);
        std::string out;
        // Without --visual-importance the checkpoint is another render's.
        const std::string plain = std::string(" ") + kSkylight +
                                  " --width 20 --height 20 --photons 3000 --quiet --no-png --integrator " + integrator;
        EXPECT_NE(run_clppm(plain + " --passes 5 -o " + d + "/x.exr --resume " + d + "/c.ck", &out), 0);
        EXPECT_NE(out.find("--visual-importance"), std::string::npos) << out;
    }
}

TEST(VisualImportance, WhatItCannotDoIsRefusedByName) {
    std::string out;
    const std::string a = std::string(" ") + kSkylight + " --width 8 --height 8 --passes 1 --quiet --no-png -o " +
                          make_temp_dir("vi-refuse") + "/x.exr --visual-importance";
    struct Case {
        const char* args;
        const char* says;
    };
    for (const Case& c :
         {Case{" --integrator pt", "needs --integrator ppm or sppm"},
          Case{" --integrator pppm", "needs --integrator ppm or sppm"}, Case{"", "needs --integrator ppm or sppm"}}) {
        EXPECT_EQ(run_clppm(a + c.args, &out), 1) << c.args << ": " << out;
        EXPECT_NE(out.find("--visual-importance"), std::string::npos) << c.args << ": " << out;
        EXPECT_NE(out.find(c.says), std::string::npos) << c.args << ": " << out;
    }
    // Two devices: a chain lives on the device that traces it every pass.
    EXPECT_EQ(
        run_command("POCL_DEVICES='pthread pthread' " + clppm_binary() + a + " --integrator sppm --device 0 --device 1",
                    &out),
        1)
        << out;
    EXPECT_NE(out.find("--visual-importance runs on one device"), std::string::npos) << out;
}

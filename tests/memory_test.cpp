// Device memory: estimated before allocation, honest against what a render really allocates, and
// within 1 GiB for SPPM and PPPM at 1920x1080 with a million photons per pass.
#include <gtest/gtest.h>

#include "integrators/memory_estimate.h"
#include "integrators/photon_map.h"
#include "medium_scenes.h"
#include "scene_builders.h"
#include "test_util.h"
#include "util/error.h"

using namespace clppm;
using namespace clppm::test;

namespace {

// A device with this much memory and this largest allocation.
DeviceInfo device_with(size_t mem, size_t max_alloc) {
    return fake_device(0, "test platform", "test device", 0, mem, max_alloc);
}

constexpr size_t GiB = size_t(1) << 30;

} // namespace

TEST(Memory, SppmAndPppmAt1080pWithAMillionPhotonsFitInOneGiB) {
    Scene scene = diffuse_box();
    for (std::string integ : {"sppm", "pppm"}) {
        RenderSettings s;
        s.integrator = integ;
        s.photons = 1000000;
        MemoryEstimate m = estimate_memory(scene, s, 1920, 1080, device_with(8 * GiB, 2 * GiB));
        EXPECT_LT(m.total(), GiB) << integ << ": " << m.total() / (1 << 20) << " MiB";
        EXPECT_NO_THROW(check_memory_fits(m, device_with(GiB + GiB / 8, GiB / 2)));
    }
}

// The estimate is what the integrators allocate: SPPM's, PT's and VCM's per-pixel buffers exactly,
// PPM's hit points within the splitting allowance, photons and light vertices within theirs.
TEST(Memory, EstimateMatchesWhatARenderAllocates) {
    for (std::string integ : {"ppm", "sppm", "pt", "vcm"}) {
        RenderSettings s;
        s.integrator = integ;
        s.width = s.height = 40;
        s.photons = 20000;
        IntegratorStats st;
        render_passes(diffuse_box(), s, 1, &st);
        MemoryEstimate m = estimate_memory(diffuse_box(), s, 40, 40, test_device());
        const double ratio = double(st.device_bytes) / double(m.integrator);
        if (integ == "ppm") {
            EXPECT_GT(ratio, 0.6) << "PPM hit points underestimated";
            EXPECT_LE(ratio, 1.05) << "PPM hit points overestimated";
        } else {
            EXPECT_NEAR(ratio, 1.0, 0.02) << integ;
        }
        if (integ != "pt") {
            EXPECT_LE(st.photon_bytes, m.photons) << integ;
        }
    }
}

// Beams along the camera rays take a second hit point slot per pixel and a second grid of the
// photons in media: the estimate counts both.
TEST(Memory, BeamsAreCountedInTheEstimate) {
    Scene fog = diffuse_box();
    set_medium(fog, {0.3f, 0.3f, 0.3f}, {0.8f, 0.8f, 0.8f}, 0.f);
    for (VolumeGather gather : {VolumeGather::Points, VolumeGather::Beams}) {
        RenderSettings s;
        s.integrator = "sppm";
        s.volume_gather = gather;
        s.width = s.height = 40;
        s.photons = 20000;
        IntegratorStats st;
        render_passes(fog, s, 1, &st);
        MemoryEstimate m = estimate_memory(fog, s, 40, 40, test_device());
        const bool beams = gather == VolumeGather::Beams;
        EXPECT_NEAR(double(st.device_bytes) / double(m.integrator), 1.0, 0.02) << beams;
        EXPECT_LE(st.photon_bytes, m.photons) << beams;
        if (beams) {
            RenderSettings points = s;
            points.volume_gather = VolumeGather::Points;
            EXPECT_GT(m.total(), estimate_memory(fog, points, 40, 40, test_device()).total());
        }
    }
}

TEST(Memory, TooLargeForTheDeviceIsAClearError) {
    RenderSettings s;
    s.integrator = "ppm";
    s.spp = 16;
    MemoryEstimate m = estimate_memory(diffuse_box(), s, 4096, 4096, device_with(GiB, GiB / 4));
    try {
        check_memory_fits(m, device_with(GiB, GiB / 4));
        FAIL() << "no error";
    } catch (const Error& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find("test device has 1024 MiB"), std::string::npos) << msg;
        EXPECT_NE(msg.find("--width/--height or --spp"), std::string::npos) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
}

// Photons are traced in batches of at most kMaxBatchPhotons: a billion photons per pass needs no
// more photon memory than four million, and the estimate says so (it used to ask for 35 GiB).
TEST(Memory, PhotonMemoryIsBoundedByTheBatchNotThePass) {
    RenderSettings big, batch;
    big.integrator = batch.integrator = "sppm";
    big.photons = 1000000000;
    batch.photons = kMaxBatchPhotons;
    const DeviceInfo dev = device_with(8 * GiB, 2 * GiB);
    const MemoryEstimate a = estimate_memory(diffuse_box(), big, 256, 256, dev);
    const MemoryEstimate b = estimate_memory(diffuse_box(), batch, 256, 256, dev);
    EXPECT_EQ(a.photons, b.photons);
    EXPECT_LT(a.photons, GiB);
    EXPECT_NO_THROW(check_memory_fits(a, dev));
}

#include "memory_estimate.h"

#include <algorithm>

#include "error.h"
#include "photon_map.h"
#include "shared_types.h"

namespace clppm {

namespace {

constexpr double kPpmHitpointsPerSample = 1.25; // splits at glass and metal: measured ~1.1 in the Cornell box
constexpr size_t kMiB = size_t(1) << 20;

std::string mib(size_t bytes) { return std::to_string((bytes + kMiB - 1) / kMiB) + " MiB"; }

} // namespace

size_t integrator_bytes_per_pixel(const RenderSettings& s) {
    const size_t film = 16; // float4 image
    switch (s.integrator) {
    case Integrator::PT: return 3 * sizeof(double) + film;
    case Integrator::SPPM:
    case Integrator::PPPM: // visible point, seen emission, statistics, pass flux
        return sizeof(dev::HitPoint) + 16 + sizeof(dev::HitStats) + sizeof(dev::PassFlux) + film;
    default: // per pixel: first index, emission, film; per hit point: point, statistics, pass flux
        return 4 + 16 + film + size_t(kPpmHitpointsPerSample * s.spp *
                                      (sizeof(dev::HitPoint) + sizeof(dev::HitStats) + sizeof(dev::PassFlux)));
    }
}

MemoryEstimate estimate_memory(const Scene& scene, const RenderSettings& settings, unsigned width, unsigned height,
                               const DeviceInfo& device) {
    MemoryEstimate m;
    const size_t tris = scene.num_triangles();
    // A wide BVH has about one node per two triangles at most.
    m.scene = tris * (3 * 16 + sizeof(dev::TriShading)) + (tris / 2 + 1) * sizeof(dev::BvhNode) +
              scene.texels.size() * 16 + scene.materials.size() * sizeof(dev::Material) + tris * sizeof(dev::Light);
    const size_t pixels = size_t(width) * height;
    m.integrator = pixels * integrator_bytes_per_pixel(settings);
    if (settings.integrator != Integrator::PT) {
        // PhotonMap's budget: as many photons as the pass needs, within a quarter of the device.
        const size_t wanted = size_t(settings.photons) * kStoredPerEmitted * 2 * sizeof(dev::Photon);
        size_t buckets = 1024; // a power of two >= the stored photons (PhotonMap::build_grid)
        while (buckets < size_t(settings.photons) * kStoredPerEmitted) buckets <<= 1;
        const size_t table = (2 * buckets + 1) * sizeof(cl_uint);
        m.photons = std::min<size_t>(wanted, device.global_mem / 4) + table;
    }
    const size_t per_hit = settings.integrator == Integrator::PPM ? size_t(kPpmHitpointsPerSample * settings.spp) : 1;
    m.largest_buffer = std::max({pixels * per_hit * sizeof(dev::HitStats), tris * sizeof(dev::TriShading),
                                 m.photons / 2});
    return m;
}

void check_memory_fits(const MemoryEstimate& m, const DeviceInfo& device) {
    const std::string breakdown = " (scene " + mib(m.scene) + ", hit points and film " + mib(m.integrator) +
                                  ", photons " + mib(m.photons) + ")";
    if (m.total() > device.global_mem * 9 / 10)
        throw Error("the render needs about " + mib(m.total()) + " of device memory" + breakdown + " but " + device.name +
                    " has " + mib(device.global_mem) + "; lower --width/--height or --spp (photons are batched to fit)");
    if (m.largest_buffer > device.max_alloc)
        throw Error("the render needs a " + mib(m.largest_buffer) + " buffer but " + device.name +
                    " allocates at most " + mib(device.max_alloc) + " at once; lower --width/--height or --spp");
}

} // namespace clppm

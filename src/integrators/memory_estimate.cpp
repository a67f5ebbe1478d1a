#include "integrators/memory_estimate.h"

#include <algorithm>

#include "integrators/integrator_table.h"
#include "shared_types.h"
#include "util/error.h"

namespace clppm {

namespace {

constexpr size_t kMiB = size_t(1) << 20;

std::string mib(size_t bytes) { return std::to_string((bytes + kMiB - 1) / kMiB) + " MiB"; }

} // namespace

MemoryEstimate estimate_memory(const Scene& scene, const RenderSettings& settings, unsigned width, unsigned height,
                               const DeviceInfo& device, bool error_estimation) {
    MemoryEstimate m;
    const size_t tris = scene.num_triangles();
    // A wide BVH has about one node per two triangles at most, and a triangle block per leaf.
    m.scene = tris * (3 * 16 + sizeof(dev::TriShading)) + (tris / 2 + 1) * sizeof(dev::BvhNode) +
              (tris / 2 + 1) * sizeof(dev::BvhTriBlock) + scene.texels.size() * 16 + scene.tangents.size() * 16 +
              scene.colors.size() * 16 + scene.uv1.size() * 8 + scene.materials.size() * sizeof(dev::Material) +
              tris * sizeof(dev::Light);
    // An environment map's sampling distribution: about two floats per texel (environment.h).
    if (scene.environment.present && scene.environment.texture >= 0) {
        const dev::Texture& t = scene.textures[size_t(scene.environment.texture)];
        m.scene += (2 * size_t(t.width) + 3) * t.height * sizeof(float);
    }
    const IntegratorRow& row = integrator_row(settings.integrator);
    const size_t pixels = size_t(width) * height;
    const IntegratorMemory own = row.memory(settings, pixels, error_estimation);
    m.integrator = own.bytes;
    // Photons or light vertices: two buffers of them (traced and sorted) and their grid.
    m.photons = row.transport_memory(settings, pixels, device);
    m.largest_buffer = std::max({own.largest_buffer, tris * sizeof(dev::TriShading), m.photons / 2});
    return m;
}

void check_memory_fits(const MemoryEstimate& m, const DeviceInfo& device) {
    const std::string breakdown =
        " (scene " + mib(m.scene) + ", hit points and film " + mib(m.integrator) + ", photons " + mib(m.photons) + ")";
    if (m.total() > device.global_mem * 9 / 10)
        throw Error("the render needs about " + mib(m.total()) + " of device memory" + breakdown + " but " +
                    device.name + " has " + mib(device.global_mem) +
                    "; lower --width/--height or --spp (photons are batched to fit)");
    if (m.largest_buffer > device.max_alloc)
        throw Error("the render needs a " + mib(m.largest_buffer) + " buffer but " + device.name +
                    " allocates at most " + mib(device.max_alloc) + " at once; lower --width/--height or --spp");
}

} // namespace clppm

// The scene on the device: BVH, triangles in leaf order, shading data, materials, textures,
// lights with their power distribution, the camera and the scene constants.
#pragma once
#include <string>
#include <vector>

#include "device/cl.h"
#include "device/device.h"
#include "scene/scene.h"
#include "scene/scene_settings.h"
#include "shared_types.h"

namespace clppm {

struct DeviceScene {
    dev::SceneInfo info{};
    dev::Camera camera{};
    std::vector<dev::Light> lights;
    std::vector<float> light_cdf; // num_lights + 1 entries, 0 .. 1
    float bounds_min[3] = {0, 0, 0}, bounds_max[3] = {0, 0, 0};
    double bvh_build_seconds = 0;
    size_t bvh_nodes = 0;
    size_t num_triangles = 0;
    size_t device_bytes = 0;
    bool media = false;                // a participating medium: the world's or a scattering mesh's (medium.h)
    std::vector<std::string> notes;    // things the user should be told (default camera, ...)
    std::vector<std::string> warnings; // things the user must be told, --quiet or not (dropped lights)

    cl::Buffer bvh_nodes_buf, tri_blocks_buf, tris_buf, shading_buf, materials_buf, textures_buf, texels_buf,
        tangents_buf, colors_buf, uv1_buf, lights_buf, light_cdf_buf, info_buf, camera_buf;

    // The same scene on another device (another context): every buffer copied through the host.
    DeviceScene clone_to(const DeviceContext& from, const DeviceContext& to) const;

    // Sets the SCENE_PARAMS arguments (kernels/scene.cl) starting at argument `first`; returns the
    // index of the next argument.
    int set_scene_args(cl::Kernel& k, int first = 0) const;
};

// Builds the BVH (reordering `scene`'s triangles into leaf order), finds the emissive triangles,
// sets up the camera for the requested resolution, and uploads everything. Throws Error for a
// scene that cannot be rendered (no lights, camera index out of range).
DeviceScene upload_scene(const DeviceContext& dc, Scene& scene, const SceneSettings& settings);

struct ImageResolution {
    unsigned width = 0, height = 0;
};

// The image size of a render: settings, else height 512 and width by the camera's aspect. Throws
// Error for a camera index the scene does not have.
ImageResolution image_resolution(const Scene& scene, const SceneSettings& settings);

// The camera a render uses: scene.cameras[index], or a default view of the whole scene when the
// file has none (noted in *note). Resolution: settings, else height 512 and width by aspect.
dev::Camera make_camera(const Scene& scene, const SceneSettings& settings, const float bmin[3], const float bmax[3],
                        std::string* note);

// Reorders every per-triangle array of `scene` so that new triangle i is old triangle order[i].
void permute_triangles(Scene& scene, const std::vector<uint32_t>& order);

} // namespace clppm

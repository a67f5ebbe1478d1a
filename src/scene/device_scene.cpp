#include "scene/device_scene.h"
#include "device/kernel_launch.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "scene/bvh_build.h"
#include "scene/environment.h"
#include "scene/light_power.h"
#include "scene/medium.h"
#include "scene/volume_nesting.h"
#include "util/error.h"
#include "util/narrow_to_float.h"

namespace clppm {

namespace {

constexpr double kPi = 3.14159265358979323846;
// The scene sizes clppm renders (upload_scene): the areas of triangles a millionth of the scene
// across stay far above the smallest normal float (1.2e-38), and the largest far below 3.4e38.
constexpr double kMinSceneRadius = 1e-12, kMaxSceneRadius = 1e12;

struct V3 {
    double x, y, z;
};
V3 v3(const Vec3& v) { return {v.x, v.y, v.z}; }
V3 sub(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double length(V3 a) { return std::sqrt(dot(a, a)); }
V3 normalize(V3 a) {
    double l = length(a);
    return l > 0 ? V3{a.x / l, a.y / l, a.z / l} : V3{0, 0, 1};
}
void store4(float out[4], V3 v, float w = 0.f) {
    out[0] = float(v.x), out[1] = float(v.y), out[2] = float(v.z), out[3] = w;
}

template <class T>
cl::Buffer upload(const DeviceContext& dc, const std::vector<T>& data, size_t* bytes) {
    size_t n = std::max<size_t>(1, data.size()) * sizeof(T); // OpenCL forbids empty buffers
    cl::Buffer b = make_buffer(dc.context, CL_MEM_READ_ONLY, n);
    if (!data.empty()) dc.queue.enqueueWriteBuffer(b, CL_TRUE, 0, data.size() * sizeof(T), data.data());
    *bytes += n;
    return b;
}

double mean_rgb(const float c[3]) { return (double(c[0]) + c[1] + c[2]) / 3.0; }

// Emissive triangles become area lights, punctual lights keep their parameters; power (mean over
// RGB, watts) decides how often each light emits photons and is sampled for direct light.
// Watts as a short number ("3.4e+38", not 39 digits).
std::string watts(double w) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g W", w);
    return buf;
}

// Every light that emits nothing is dropped, and *dropped says which and why.
std::vector<dev::Light> collect_lights(const Scene& scene, const dev::SceneInfo& info,
                                       std::vector<std::string>* dropped) {
    std::vector<dev::Light> lights;
    size_t zero_area = 0;
    for (size_t t = 0; t < scene.num_triangles(); ++t) {
        const dev::Material& m = scene.materials[scene.shading[t].material];
        double le = mean_rgb(m.emission);
        if (le > 0 && m.emissive_tex >= 0) le = textured_emission_mean(scene, t);
        if (!(le > 0)) continue;
        V3 p0 = v3(scene.positions[3 * t]), p1 = v3(scene.positions[3 * t + 1]), p2 = v3(scene.positions[3 * t + 2]);
        double area = 0.5 * length(cross(sub(p1, p0), sub(p2, p0)));
        if (!(area > 0)) {
            ++zero_area;
            continue;
        }
        dev::Light l{};
        l.type = LIGHT_TRIANGLE;
        l.prim = uint32_t(t);
        l.two_sided = (m.flags & MATERIAL_FLAG_DOUBLE_SIDED) ? 1u : 0u;
        l.area = float(area);
        for (int k = 0; k < 3; ++k) l.radiance[k] = m.emission[k];
        const double power = le * area * kPi * (l.two_sided ? 2 : 1); // Phi = Le A pi per side
        if (!std::isfinite(narrow_to_float(power)))
            throw Error(scene.source + ": an emissive triangle's power (" + watts(power) +
                        ") does not fit a float; scale the emission or the geometry down");
        l.power = float(power);
        lights.push_back(l);
    }
    if (zero_area) dropped->push_back(std::to_string(zero_area) + " emissive triangle(s) of zero area");
    static const char* const kKind[] = {"area", "point", "spot", "directional"};
    for (size_t i = 0; i < scene.punctual_lights.size(); ++i) {
        dev::Light l = scene.punctual_lights[i];
        const double power = punctual_light_power(l, double(info.radius));
        l.power = narrow_to_float(power);
        const std::string what = std::string(kKind[std::min<uint32_t>(l.type, 3)]) + " light " + std::to_string(i);
        if (!std::isfinite(l.power))
            throw Error(scene.source + ": " + what + "'s power (" + watts(power) +
                        ") does not fit a float; scale its intensity down");
        if (l.power > 0) lights.push_back(l);
        else dropped->push_back(what + " emits nothing (zero intensity or a closed cone)");
    }
    return lights;
}

} // namespace

void permute_triangles(Scene& scene, const std::vector<uint32_t>& order) {
    std::vector<Vec3> positions(scene.positions.size());
    std::vector<dev::TriShading> shading(scene.shading.size());
    std::vector<std::array<float, 4>> tangents(scene.tangents.size()), colors(scene.colors.size());
    std::vector<std::array<float, 2>> uv1(scene.uv1.size());
    for (size_t i = 0; i < order.size(); ++i) {
        for (int k = 0; k < 3; ++k) positions[3 * i + k] = scene.positions[3 * size_t(order[i]) + k];
        shading[i] = scene.shading[order[i]];
        if (!tangents.empty())
            for (int k = 0; k < 3; ++k) tangents[3 * i + k] = scene.tangents[3 * size_t(order[i]) + k];
        if (!colors.empty())
            for (int k = 0; k < 3; ++k) colors[3 * i + k] = scene.colors[3 * size_t(order[i]) + k];
        if (!uv1.empty())
            for (int k = 0; k < 3; ++k) uv1[3 * i + k] = scene.uv1[3 * size_t(order[i]) + k];
    }
    scene.positions.swap(positions);
    scene.shading.swap(shading);
    scene.tangents.swap(tangents);
    scene.colors.swap(colors);
    scene.uv1.swap(uv1);
}

namespace {

// The scene's camera settings.camera, or null when the scene has none (then only camera 0, the
// default view, may be asked for).
const CameraDesc* chosen_camera(const Scene& scene, const SceneSettings& settings) {
    if (scene.cameras.empty()) {
        if (settings.camera != 0)
            throw Error("--camera " + std::to_string(settings.camera) + ": the scene has no camera");
        return nullptr;
    }
    if (settings.camera >= scene.cameras.size())
        throw Error("--camera " + std::to_string(settings.camera) + ": the scene has " +
                    std::to_string(scene.cameras.size()) + " camera(s), indices 0.." +
                    std::to_string(scene.cameras.size() - 1));
    return &scene.cameras[settings.camera];
}

} // namespace

ImageResolution image_resolution(const Scene& scene, const SceneSettings& settings) {
    const CameraDesc* desc = chosen_camera(scene, settings);
    unsigned w = settings.width, h = settings.height;
    double aspect = desc && desc->aspect > 0 ? desc->aspect : 0;
    if (w == 0 && h == 0) {
        h = 512;
        w = aspect > 0 ? unsigned(std::lround(h * aspect)) : 512;
    } else if (w == 0) {
        w = aspect > 0 ? unsigned(std::lround(h * aspect)) : h;
    } else if (h == 0) {
        h = aspect > 0 ? unsigned(std::lround(w / aspect)) : w;
    }
    return {std::max(1u, w), std::max(1u, h)};
}

dev::Camera make_camera(const Scene& scene, const SceneSettings& settings, const float bmin[3], const float bmax[3],
                        std::string* note) {
    CameraDesc desc;
    if (const CameraDesc* chosen = chosen_camera(scene, settings)) {
        desc = *chosen;
    } else {
        // Default view: from +Z towards the centre of the bounds, the bounding sphere filling the
        // vertical field of view.
        V3 c{0.5 * (bmin[0] + bmax[0]), 0.5 * (bmin[1] + bmax[1]), 0.5 * (bmin[2] + bmax[2])};
        double r = 0.5 * length(V3{double(bmax[0]) - bmin[0], double(bmax[1]) - bmin[1], double(bmax[2]) - bmin[2]});
        desc.yfov = 0.8f;
        double d = r / std::sin(desc.yfov / 2) * 1.05;
        desc.position[0] = float(c.x), desc.position[1] = float(c.y), desc.position[2] = float(c.z + d);
        if (note) *note = "no camera in the scene: using the default view from +Z at distance " + std::to_string(d);
    }
    const auto [w, h] = image_resolution(scene, settings);
    // The vertical field of view is the camera's; the horizontal one follows the image shape.
    V3 f = normalize(V3{desc.forward[0], desc.forward[1], desc.forward[2]});
    V3 up = V3{desc.up[0], desc.up[1], desc.up[2]};
    V3 right = normalize(cross(f, up));
    up = cross(right, f);
    // Orthographic: right and up are the view's half extents in world units (ymag kept, the width
    // following the image shape as a perspective camera's horizontal field of view does).
    double ty = desc.orthographic ? double(desc.ymag) : std::tan(desc.yfov / 2), tx = ty * double(w) / h;
    dev::Camera cam{};
    store4(cam.origin, V3{desc.position[0], desc.position[1], desc.position[2]});
    store4(cam.forward, f);
    store4(cam.right, V3{right.x * tx, right.y * tx, right.z * tx});
    store4(cam.up, V3{up.x * ty, up.y * ty, up.z * ty});
    cam.origin[3] = desc.znear;                     // kernels/camera.cl: rays start at the clip plane
    cam.forward[3] = desc.orthographic ? 1.f : 0.f; // and are parallel
    cam.width = w, cam.height = h;
    cam.lens_radius = float(settings.aperture >= 0 ? settings.aperture : desc.aperture_radius);
    if (desc.orthographic) {
        if (cam.lens_radius > 0.f && settings.aperture > 0)
            throw Error("--aperture: the camera is orthographic, which has no lens");
        cam.lens_radius = 0.f;
    }
    double focus = settings.focus_distance > 0 ? settings.focus_distance : desc.focus_distance;
    if (!(focus > 0)) { // the plane through the centre of the scene
        V3 c{0.5 * (bmin[0] + bmax[0]), 0.5 * (bmin[1] + bmax[1]), 0.5 * (bmin[2] + bmax[2])};
        focus = std::max(1e-6, dot(sub(c, V3{desc.position[0], desc.position[1], desc.position[2]}), f));
    }
    cam.focus_distance = float(focus);
    return cam;
}

namespace {

cl::Buffer copy_buffer(const cl::Buffer& src, const DeviceContext& from, const DeviceContext& to) {
    const size_t bytes = src.getInfo<CL_MEM_SIZE>();
    std::vector<unsigned char> data(bytes);
    from.queue.enqueueReadBuffer(src, CL_TRUE, 0, bytes, data.data());
    cl::Buffer dst = make_buffer(to.context, CL_MEM_READ_ONLY, bytes);
    to.queue.enqueueWriteBuffer(dst, CL_TRUE, 0, bytes, data.data());
    return dst;
}

} // namespace

namespace {

// The buffers kernels receive as SCENE_PARAMS (kernels/scene.cl), in its order: the one list
// both set_scene_args and clone_to go by, so a new scene buffer cannot be left out of either.
const std::array<cl::Buffer DeviceScene::*, 13> kSceneBuffers = {
    &DeviceScene::bvh_nodes_buf, &DeviceScene::tri_blocks_buf, &DeviceScene::tris_buf,   &DeviceScene::shading_buf,
    &DeviceScene::materials_buf, &DeviceScene::textures_buf,   &DeviceScene::texels_buf, &DeviceScene::tangents_buf,
    &DeviceScene::colors_buf,    &DeviceScene::uv1_buf,        &DeviceScene::lights_buf, &DeviceScene::light_cdf_buf,
    &DeviceScene::info_buf};

} // namespace

DeviceScene DeviceScene::clone_to(const DeviceContext& from, const DeviceContext& to) const {
    DeviceScene c = *this; // host-side values
    for (cl::Buffer DeviceScene::*b : kSceneBuffers) c.*b = copy_buffer(this->*b, from, to);
    c.camera_buf = copy_buffer(camera_buf, from, to);
    return c;
}

int DeviceScene::set_scene_args(cl::Kernel& k, int a) const {
    for (cl::Buffer DeviceScene::*b : kSceneBuffers) k.setArg(a++, this->*b);
    return a;
}

DeviceScene upload_scene(const DeviceContext& dc, Scene& scene, const SceneSettings& settings) {
    DeviceScene ds;
    if (!scene.volumes_nested) nest_volumes(scene); // which volume each surface lies in (kernels/medium.cl)
    scene.volumes_nested = true;
    BvhBuildResult bvh = build_bvh(scene.positions);
    permute_triangles(scene, bvh.tri_order);
    ds.bvh_build_seconds = bvh.build_seconds;
    ds.bvh_nodes = bvh.nodes.size();
    ds.num_triangles = scene.num_triangles();

    // Bounds and the bounding sphere: ray offsets and grid cells are relative to them.
    float lo[3] = {std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
                   std::numeric_limits<float>::max()};
    float hi[3] = {-lo[0], -lo[1], -lo[2]};
    for (const Vec3& p : scene.positions) {
        const float c[3] = {p.x, p.y, p.z};
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], c[k]), hi[k] = std::max(hi[k], c[k]);
    }
    if (scene.positions.empty()) std::fill(lo, lo + 3, 0.f), std::fill(hi, hi + 3, 0.f);
    std::copy(lo, lo + 3, ds.bounds_min);
    std::copy(hi, hi + 3, ds.bounds_max);
    V3 center{0.5 * (lo[0] + double(hi[0])), 0.5 * (lo[1] + double(hi[1])), 0.5 * (lo[2] + double(hi[2]))};
    double radius = 0.5 * length(V3{double(hi[0]) - lo[0], double(hi[1]) - lo[1], double(hi[2]) - lo[2]});
    if (!(radius > 0)) radius = 1;
    // Triangle areas, light power and ray offsets are floats relative to the scene's size: far
    // outside this range they underflow to a black image or overflow, so such a scene is refused.
    if (radius < kMinSceneRadius || radius > kMaxSceneRadius) {
        char msg[200];
        std::snprintf(msg, sizeof msg,
                      ": the scene's bounding sphere has radius %.3g; clppm renders scenes of radius %.0e to %.0e "
                      "(float areas and ray offsets): scale the scene",
                      radius, kMinSceneRadius, kMaxSceneRadius);
        throw Error(scene.source + msg);
    }
    store4(ds.info.center, center);
    ds.info.radius = float(radius);
    ds.info.ray_eps = float(radius * 1e-5);
    ds.info.num_tris = uint32_t(scene.num_triangles());
    ds.info.max_bounces = settings.max_bounces;
    ds.info.vertex_colors = scene.colors.empty() ? 0u : 1u;
    ds.info.texcoord1 = scene.uv1.empty() ? 0u : 1u;
    ds.media = scene_has_media(scene);
    if (scene.medium.present) { // kernels/medium.cl
        const MediumDesc& m = scene.medium.medium;
        for (int k = 0; k < 3; ++k) {
            ds.info.medium_sigma_t[k] = m.density[size_t(k)];
            ds.info.medium_albedo[k] = m.albedo[size_t(k)];
        }
        ds.info.medium_sigma_t[3] = 1.f;
        ds.info.medium_albedo[3] = m.anisotropy;
    }

    std::vector<std::string> dropped;
    ds.lights = collect_lights(scene, ds.info, &dropped);
    ds.info.env_light = ENV_UNIFORM;
    EnvDistribution env_dist;
    if (scene.environment.present) {
        const Environment& e = scene.environment;
        dev::Light l{};
        l.type = LIGHT_ENVIRONMENT;
        l.prim = ENV_UNIFORM;
        double integral = 4 * M_PI; // of the texels (uniform: 1), before the factor
        if (e.texture >= 0) {
            const dev::Texture& t = scene.textures[size_t(e.texture)];
            env_dist = env_distribution(scene.texels, t.offset, t.width, t.height);
            integral = env_dist.integral;
            l.prim = uint32_t(e.texture);
        }
        for (int c = 0; c < 3; ++c) l.radiance[c] = e.radiance[size_t(c)];
        l.position[0] = std::cos(e.rotation), l.position[1] = std::sin(e.rotation);
        l.position[2] = e.hidden ? 1.f : 0.f;
        // pi R^2 int L dw: what crosses the disc photons start from (kernels/lights.cl).
        const double mean = (double(e.radiance[0]) + e.radiance[1] + e.radiance[2]) / 3;
        const double power = M_PI * double(ds.info.radius) * ds.info.radius * integral * mean;
        l.power = narrow_to_float(power);
        if (!std::isfinite(l.power))
            throw Error(e.source + ": the environment's power (" + watts(power) + ") does not fit a float");
        if (l.power > 0) {
            ds.info.env_light = uint32_t(ds.lights.size());
            ds.lights.push_back(l);
        } else {
            dropped.push_back(e.source + " (black)");
        }
    }
    // A scene whose only light is what unlit surfaces show (KHR_materials_unlit) renders without
    // lights: they show their colour to the camera, and nothing else is lit.
    bool unlit = false;
    for (const dev::TriShading& t : scene.shading)
        if (t.material < scene.materials.size() && (scene.materials[t.material].flags & MATERIAL_FLAG_UNLIT)) {
            unlit = true;
            break;
        }
    if (ds.lights.empty() && !unlit) {
        std::string why;
        for (const std::string& d : dropped) why += (why.empty() ? "; dropped: " : ", ") + d;
        throw Error(scene.source +
                    ": no lights (no emissive material and no KHR_lights_punctual light): nothing to render" + why +
                    "; light it with --env FILE or --env-color R,G,B");
    }
    for (const std::string& d : dropped) ds.warnings.push_back("light dropped: " + d);
    double total = 0;
    for (const dev::Light& l : ds.lights) total += l.power;
    ds.light_cdf.assign(1, 0.f);
    double run = 0;
    for (const dev::Light& l : ds.lights) {
        run += l.power;
        ds.light_cdf.push_back(float(run / total));
    }
    ds.light_cdf.back() = 1.f;
    // The environment's sampling distribution follows the lights' CDF.
    if (ds.info.env_light != ENV_UNIFORM && !env_dist.data.empty()) {
        ds.lights[ds.info.env_light].two_sided = uint32_t(ds.light_cdf.size());
        ds.light_cdf.insert(ds.light_cdf.end(), env_dist.data.begin(), env_dist.data.end());
    }
    if (!std::isfinite(narrow_to_float(total)))
        throw Error(scene.source + ": the lights' total power (" + watts(total) +
                    ") does not fit a float; scale the lights down");
    ds.info.total_power = float(total);
    ds.info.num_lights = uint32_t(ds.lights.size());
    for (const dev::Light& l : ds.lights) ds.info.num_emissive_tris += l.type == LIGHT_TRIANGLE;

    std::string note;
    ds.camera = make_camera(scene, settings, lo, hi, &note);
    if (!note.empty()) ds.notes.push_back(note);

    std::vector<std::array<float, 4>> tri_data = bvh_triangle_data(scene.positions);
    const std::vector<dev::BvhTriBlock> blocks = bvh_leaf_blocks(bvh.nodes, scene.positions);
    size_t& bytes = ds.device_bytes;
    ds.bvh_nodes_buf = upload(dc, bvh.nodes, &bytes);
    ds.tri_blocks_buf = upload(dc, blocks, &bytes);
    ds.tris_buf = upload(dc, tri_data, &bytes);
    ds.shading_buf = upload(dc, scene.shading, &bytes);
    ds.materials_buf = upload(dc, scene.materials, &bytes);
    ds.textures_buf = upload(dc, scene.textures, &bytes);
    ds.texels_buf = upload(dc, scene.texels, &bytes);
    ds.tangents_buf = upload(dc, scene.tangents, &bytes);
    ds.colors_buf = upload(dc, scene.colors, &bytes);
    ds.uv1_buf = upload(dc, scene.uv1, &bytes);
    ds.lights_buf = upload(dc, ds.lights, &bytes);
    ds.light_cdf_buf = upload(dc, ds.light_cdf, &bytes);
    ds.info_buf = upload(dc, std::vector<dev::SceneInfo>{ds.info}, &bytes);
    ds.camera_buf = upload(dc, std::vector<dev::Camera>{ds.camera}, &bytes);
    return ds;
}

} // namespace clppm

#include "scene/environment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/image_io.h"
#include "io/radiance_hdr.h"
#include "io/regular_file.h"
#include "scene/studio_environment.h"
#include "scene/used_materials.h"
#include "util/error.h"
#include "util/text.h"

namespace clppm {

namespace {

// The map as linear RGB rows, top first; `label` names it in messages ("--env FILE" or the
// scene's extras).
Image read_map(const std::string& path, const std::string& label) {
    if (const std::string why = not_a_regular_file(path); !why.empty()) throw Error(label + ": " + why);
    if (ends_with_ci(path, ".exr")) return read_exr(path);
    if (ends_with_ci(path, ".hdr")) {
        try {
            return read_radiance_hdr(path);
        } catch (const Error& e) {
            throw Error(label + ": " + e.what());
        }
    }
    throw Error(label + ": not an equirectangular .exr or .hdr file");
}

constexpr const char* kStudio = "studio"; // --env studio: the built-in studio, not a file

} // namespace

bool scene_has_lights(const Scene& scene) {
    const std::vector<bool> used = used_materials(scene);
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        const dev::Material& m = scene.materials[i];
        if (used[i] && (m.emission[0] > 0.f || m.emission[1] > 0.f || m.emission[2] > 0.f)) return true;
    }
    for (const dev::Light& l : scene.punctual_lights)
        if (l.radiance[0] > 0.f || l.radiance[1] > 0.f || l.radiance[2] > 0.f) return true;
    return false;
}

void apply_environment(Scene& scene, const EnvironmentSettings& s, std::string* note) {
    // Which world: the command line's, else the file's own (extras.clppm_environment), else the
    // default one where the scene has no lights. --env-strength and --env-rotate scale and turn
    // whichever it is.
    const FileWorld& fw = scene.file_world;
    const bool from_file = s.file.empty() && !s.has_color && s.default_light && fw.kind != FileWorld::Kind::None;
    const std::string file_label = scene.source + ": extras.clppm_environment";
    std::string map = s.file, label = "--env " + s.file, source = s.file;
    std::array<float, 3> color{1.f, 1.f, 1.f};
    bool uniform = s.has_color;
    double strength = s.strength, rotation = s.rotate_degrees;
    std::string said;
    if (s.file == kStudio) {
        label = "--env studio";
        source = "the studio environment";
        said = "world: --env studio: the built-in studio environment (a soft key light upper left, a rim light "
               "behind; irradiance pi on an upward surface, as the white world's)";
    } else if (!s.file.empty()) {
        said = "world: --env " + s.file;
    } else if (s.has_color) {
        color = s.color;
        source = "--env-color";
        said = "world: --env-color";
    } else if (from_file) {
        strength *= fw.strength;
        rotation += fw.rotation_degrees;
        if (fw.kind == FileWorld::Kind::Image) {
            map = fw.image;
            label = file_label + ".image " + fw.image;
            source = fw.image;
            said = "world: " + file_label + ": the map " + fw.image + ", strength " + number_text(strength) +
                   ", rotation " + number_text(rotation) + " degrees";
        } else {
            color = fw.color;
            uniform = true;
            source = "the file's extras.clppm_environment";
            said = "world: " + file_label + ": colour " + number_text(color[0]) + "," + number_text(color[1]) + "," +
                   number_text(color[2]) + (strength != 1.0 ? " x " + number_text(strength) : std::string());
        }
    } else if (s.default_light) {
        // As every glTF viewer shows a model: under an environment, besides its own lights.
        uniform = true;
        source = "the default environment";
        said = "world: the default environment, uniform white of radiance " + number_text(strength) +
               " (as a Blender world of strength " + number_text(strength) + "): " + scene.source +
               " sets no world of its own" +
               (scene_has_lights(scene) ? " (extras.clppm_environment; --no-default-light: its own lights alone)"
                                        : " and has no lights (--no-default-light refuses it)");
    } else {
        if (note) *note = "world: none (--no-default-light): the scene's own lights alone";
        return;
    }
    if (note) *note = said;
    Environment env;
    env.rotation = float(rotation * M_PI / 180.0);
    env.hidden = s.hidden;
    env.source = source;
    const float k = float(strength);
    if (!uniform) {
        const Image img = map == kStudio && s.file == kStudio ? studio_environment() : read_map(map, label);
        if (img.width <= 0 || img.height <= 0) throw Error(label + ": the image is empty");
        dev::Texture t{};
        t.offset = uint32_t(scene.texels.size());
        t.width = uint32_t(img.width), t.height = uint32_t(img.height);
        t.xform[0] = t.xform[4] = 1.f;
        for (size_t i = 0; i < size_t(img.width) * size_t(img.height); ++i) {
            std::array<float, 4> px{img.rgb[3 * i], img.rgb[3 * i + 1], img.rgb[3 * i + 2], 1.f};
            for (int c = 0; c < 3; ++c)
                if (!std::isfinite(px[size_t(c)]) || px[size_t(c)] < 0.f)
                    throw Error(label + ": texel " + std::to_string(i) +
                                " is negative or not finite; an environment map holds radiance >= 0");
            scene.texels.push_back(px);
        }
        env.texture = int32_t(scene.textures.size());
        scene.textures.push_back(t);
        env.radiance = {k, k, k};
    } else {
        env.radiance = {color[0] * k, color[1] * k, color[2] * k};
        if (from_file && env.radiance == std::array<float, 3>{0.f, 0.f, 0.f}) return; // a black world: none
    }
    for (float c : env.radiance)
        if (!std::isfinite(c) || c < 0.f)
            throw Error((from_file ? file_label : std::string("--env-strength/--env-color")) +
                        ": the radiance must be finite and >= 0");
    env.present = true;
    scene.environment = env;
}

std::array<double, 3> env_direction(double u, double v) {
    // theta from +Y, phi from -Z towards +X.
    const double theta = v * M_PI, phi = (u - 0.5) * 2 * M_PI;
    return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

std::array<double, 2> env_uv(const std::array<double, 3>& d) {
    double u = 0.5 + std::atan2(d[0], -d[2]) / (2 * M_PI);
    u -= std::floor(u);
    return {u, std::acos(std::clamp(d[1], -1.0, 1.0)) / M_PI};
}

EnvDistribution env_distribution(const std::vector<std::array<float, 4>>& texels, size_t offset, unsigned W,
                                 unsigned H) {
    // f_ij = luminance x sin(theta at the row's centre); rows weigh by their sums.
    std::vector<double> f(size_t(W) * H), row(H, 0.0);
    EnvDistribution d;
    for (unsigned j = 0; j < H; ++j) {
        const double sin_c = std::sin((j + 0.5) / H * M_PI);
        // The row's exact solid angle per texel: (2 pi / W)(cos theta0 - cos theta1).
        const double omega = 2 * M_PI / W * (std::cos(j * M_PI / H) - std::cos((j + 1) * M_PI / H));
        for (unsigned i = 0; i < W; ++i) {
            const std::array<float, 4>& t = texels[offset + size_t(j) * W + i];
            const double y = 0.2126 * t[0] + 0.7152 * t[1] + 0.0722 * t[2];
            // A texel with colour but no luminance (pure blue in some maps) still gets drawn.
            const double w = std::max(y, (double(t[0]) + t[1] + t[2]) * 1e-3);
            f[size_t(j) * W + i] = w * sin_c;
            row[j] += f[size_t(j) * W + i];
            d.integral += (double(t[0]) + t[1] + t[2]) / 3 * omega;
        }
    }
    double total = 0;
    for (double r : row) total += r;
    std::vector<float>& out = d.data;
    out.reserve(2 * size_t(H) + 1 + size_t(H) * (2 * size_t(W) + 1));
    // The marginal over rows and its densities over v (a black map: uniform, never drawn from
    // since its power is 0).
    double run = 0;
    out.push_back(0.f);
    for (unsigned j = 0; j < H; ++j) {
        run += total > 0 ? row[j] : 1.0;
        out.push_back(float(run / (total > 0 ? total : double(H))));
    }
    out[H] = 1.f;
    for (unsigned j = 0; j < H; ++j) out.push_back(float((total > 0 ? row[j] / total : 1.0 / H) * H));
    std::vector<float> pdfs;
    for (unsigned j = 0; j < H; ++j) {
        const size_t first = out.size();
        double acc = 0;
        out.push_back(0.f);
        for (unsigned i = 0; i < W; ++i) {
            acc += row[j] > 0 ? f[size_t(j) * W + i] : 1.0;
            out.push_back(float(acc / (row[j] > 0 ? row[j] : double(W))));
        }
        out[first + W] = 1.f;
        for (unsigned i = 0; i < W; ++i)
            pdfs.push_back(float((row[j] > 0 ? f[size_t(j) * W + i] / row[j] : 1.0 / W) * W));
    }
    out.insert(out.end(), pdfs.begin(), pdfs.end());
    return d;
}

} // namespace clppm

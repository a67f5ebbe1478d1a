#include "scene/environment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/image_io.h"
#include "io/radiance_hdr.h"
#include "io/regular_file.h"
#include "util/error.h"

namespace clppm {

namespace {

bool ends_with(const std::string& s, const std::string& tail) {
    if (s.size() < tail.size()) return false;
    std::string end = s.substr(s.size() - tail.size());
    std::transform(end.begin(), end.end(), end.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return end == tail;
}

// The map as linear RGB rows, top first.
Image read_map(const std::string& path) {
    if (const std::string why = not_a_regular_file(path); !why.empty()) throw Error("--env " + path + ": " + why);
    if (ends_with(path, ".exr")) return read_exr(path);
    if (ends_with(path, ".hdr")) {
        try {
            return read_radiance_hdr(path);
        } catch (const Error& e) {
            throw Error("--env " + path + ": " + e.what());
        }
    }
    throw Error("--env " + path + ": not an equirectangular .exr or .hdr file");
}

} // namespace

bool scene_has_lights(const Scene& scene) {
    std::vector<bool> used(scene.materials.size(), false);
    for (const dev::TriShading& t : scene.shading)
        if (t.material < used.size()) used[t.material] = true;
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        const dev::Material& m = scene.materials[i];
        if (used[i] && (m.emission[0] > 0.f || m.emission[1] > 0.f || m.emission[2] > 0.f)) return true;
    }
    for (const dev::Light& l : scene.punctual_lights)
        if (l.radiance[0] > 0.f || l.radiance[1] > 0.f || l.radiance[2] > 0.f) return true;
    return false;
}

void apply_environment(Scene& scene, const EnvironmentSettings& s, std::string* note) {
    Environment env;
    env.rotation = float(s.rotate_degrees * M_PI / 180.0);
    env.hidden = s.hidden;
    const float k = float(s.strength);
    if (!s.file.empty()) {
        const Image img = read_map(s.file);
        if (img.width <= 0 || img.height <= 0) throw Error("--env " + s.file + ": the image is empty");
        dev::Texture t{};
        t.offset = uint32_t(scene.texels.size());
        t.width = uint32_t(img.width), t.height = uint32_t(img.height);
        t.xform[0] = t.xform[4] = 1.f;
        for (size_t i = 0; i < size_t(img.width) * size_t(img.height); ++i) {
            std::array<float, 4> px{img.rgb[3 * i], img.rgb[3 * i + 1], img.rgb[3 * i + 2], 1.f};
            for (int c = 0; c < 3; ++c)
                if (!std::isfinite(px[size_t(c)]) || px[size_t(c)] < 0.f)
                    throw Error("--env " + s.file + ": texel " + std::to_string(i) +
                                " is negative or not finite; an environment map holds radiance >= 0");
            scene.texels.push_back(px);
        }
        env.texture = int32_t(scene.textures.size());
        scene.textures.push_back(t);
        env.radiance = {k, k, k};
        env.source = s.file;
    } else if (s.has_color) {
        env.radiance = {s.color[0] * k, s.color[1] * k, s.color[2] * k};
        env.source = "--env-color";
    } else if (s.default_light && !scene_has_lights(scene)) {
        env.radiance = {k, k, k};
        env.source = "the default environment";
        if (note) {
            char k_text[32];
            std::snprintf(k_text, sizeof k_text, "%g", double(k));
            *note = scene.source + ": no lights in the scene: lit by a uniform white environment of radiance " +
                    k_text + " (as a Blender world of strength " + k_text + "); --no-default-light refuses such scenes";
        }
    } else {
        return;
    }
    for (float c : env.radiance)
        if (!std::isfinite(c) || c < 0.f)
            throw Error("--env-strength/--env-color: the radiance must be finite and >= 0");
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

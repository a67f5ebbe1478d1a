#include "scene/medium.h"

#include <cmath>
#include <vector>

#include "scene/used_materials.h"
#include "util/error.h"
#include "util/text.h"

namespace clppm {

namespace {

std::string rgb_text(const std::array<float, 3>& c) {
    if (c[0] == c[1] && c[1] == c[2]) return number_text(c[0]);
    return number_text(c[0]) + "," + number_text(c[1]) + "," + number_text(c[2]);
}

} // namespace

void apply_medium(Scene& scene, const MediumSettings& s, std::string* note) {
    scene.medium = WorldMedium{};
    if (note) note->clear();
    const bool shaped = s.has_density || s.has_albedo || s.has_anisotropy || s.scale != 1.0;
    if (s.none) {
        if (shaped) throw Error("--no-medium: remove the other --medium options, or --no-medium");
        return;
    }
    if (!scene.has_file_medium && !s.has_density) {
        if (shaped)
            throw Error("--medium-albedo, --medium-anisotropy and --medium-scale shape a medium: " + scene.source +
                        " has none (extras.clppm_medium); give --medium-density");
        return;
    }
    MediumDesc m = scene.has_file_medium ? scene.file_medium : MediumDesc{};
    std::string source = scene.has_file_medium ? scene.source + ": extras.clppm_medium" : "--medium-density";
    if (s.has_density) m.density = s.density;
    if (s.has_albedo) m.albedo = s.albedo;
    if (s.has_anisotropy) m.anisotropy = s.anisotropy;
    for (float& d : m.density) {
        const double scaled = double(d) * s.scale;
        if (!(scaled <= 3e38)) throw Error("--medium-scale: the density " + number_text(scaled) + " overflows a float");
        d = float(scaled);
    }
    if (scene.has_file_medium && (s.has_density || s.has_albedo || s.has_anisotropy || s.scale != 1.0))
        source += ", changed by the --medium options";
    if (!(m.density[0] > 0.f || m.density[1] > 0.f || m.density[2] > 0.f)) {
        if (note) *note = "medium: none (" + source + " has density 0)";
        return;
    }
    scene.medium.present = true;
    scene.medium.medium = m;
    scene.medium.source = source;
    if (note)
        *note = "medium: " + source + ": density " + rgb_text(m.density) + " per scene unit, albedo " +
                rgb_text(m.albedo) + ", anisotropy " + number_text(m.anisotropy);
}

bool scene_has_media(const Scene& scene) {
    if (scene.medium.present) return true;
    const std::vector<bool> used = used_materials(scene);
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        const dev::Material& m = scene.materials[i];
        if (used[i] && (m.scatter[0] > 0.f || m.scatter[1] > 0.f || m.scatter[2] > 0.f)) return true;
    }
    return false;
}

} // namespace clppm

// The world's participating medium: what the --medium options ask for, over the file's own
// (extras.clppm_medium), into Scene::medium. The kernels' side is kernels/medium.cl.
#pragma once
#include <array>
#include <string>

#include "scene/scene.h"

namespace clppm {

struct MediumSettings {
    bool has_density = false;       // --medium-density given
    std::array<float, 3> density{}; // --medium-density: extinction per scene unit
    bool has_albedo = false;        // --medium-albedo given
    std::array<float, 3> albedo{};  // --medium-albedo
    bool has_anisotropy = false;    // --medium-anisotropy given
    float anisotropy = 0.f;         // --medium-anisotropy: the Henyey-Greenstein g
    double scale = 1.0;             // --medium-scale: multiplies the density, the file's or the option's
    bool none = false;              // --no-medium: the file's medium removed
};

// Sets scene.medium: the file's medium (scene.file_medium) with each --medium option replacing
// its part; --medium-density makes one where the file has none (albedo 1, g 0 unless given);
// --medium-scale scales the density; --no-medium removes it. A density of 0 everywhere is no
// medium. *note says which medium and where it came from ("" for none). Throws clppm::Error for
// options that shape a medium the scene does not have, or --no-medium with them.
void apply_medium(Scene& scene, const MediumSettings& settings, std::string* note);

// Whether the scene has a participating medium: the world's (after apply_medium), or a mesh whose
// material's volume scatters (KHR_materials_volume_scatter) that some triangle uses.
bool scene_has_media(const Scene& scene);

} // namespace clppm

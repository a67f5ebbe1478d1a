// The environment light: what the --env options ask for, its map loaded into the scene's
// textures, the default white environment of a scene without lights, and the host side of
// kernels/environment.cl (its direction mapping, written independently, and the sampling
// distribution the kernels read).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace clppm {

struct EnvironmentSettings {
    std::string file;             // --env: equirectangular .exr or .hdr; empty: none
    bool has_color = false;       // --env-color given
    std::array<float, 3> color{}; // --env-color R,G,B: a uniform environment
    double strength = 1.0;        // --env-strength
    double rotate_degrees = 0.0;  // --env-rotate: about +Y, right-handed
    bool hidden = false;          // --env-hidden: camera rays see black
    bool default_light = true;    // false with --no-default-light
};

// Sets scene.environment, the world: the command line's (--env, --env-color; --no-default-light
// for none), else the file's own (scene.file_world, from extras.clppm_environment; black: none),
// else, when the scene has no light of its own, the default white environment of radiance 1.
// --env-strength and --env-rotate scale and turn whichever it is. *note says which world and
// where it came from. Throws clppm::Error naming the file or option for an unreadable, empty or
// non-finite map.
void apply_environment(Scene& scene, const EnvironmentSettings& settings, std::string* note);

// Whether the scene has an emitter of its own: a material with emission some triangle uses, or
// a punctual light of nonzero intensity.
bool scene_has_lights(const Scene& scene);

// The map's direction for (u, v) (before rotation) and back: the same conventions as
// kernels/environment.cl, written from its header's definition.
std::array<double, 3> env_direction(double u, double v);
std::array<double, 2> env_uv(const std::array<double, 3>& d);

// The sampling distribution kernels/environment.cl reads from light_cdf (layout in its header)
// for a W x H map of the given texels: luminance times sin(theta) per texel. Also the map's
// integral over the sphere, mean over RGB, of texel radiance (no strength): the light's power is
// pi R^2 times that integral times the strength.
struct EnvDistribution {
    std::vector<float> data;
    double integral = 0; // int L dw, mean over RGB
};
EnvDistribution env_distribution(const std::vector<std::array<float, 4>>& texels, size_t offset, unsigned width,
                                 unsigned height);

} // namespace clppm

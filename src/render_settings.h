// What one render is asked to do, independent of how the command line spelled it.
#pragma once
#include <cstdint>
#include <string>

#include "options.h" // Integrator, DirectLighting

namespace clppm {

struct RenderSettings {
    Integrator integrator = Integrator::PPM;
    DirectLighting direct = DirectLighting::Sample;
    unsigned width = 0, height = 0; // 0: from the camera (height 512, width by aspect)
    unsigned camera = 0;
    unsigned spp = 1;               // hit points (PPM) per pixel
    uint64_t photons = 200000;      // photons per pass (M)
    double alpha = 0.7;
    double radius = 0;              // initial radius in world units; 0: heuristic
    uint64_t seed = 1;
    unsigned max_bounces = 16;
    PixelFilter filter = PixelFilter::Box;
    double aperture = -1;           // thin-lens radius; < 0: the camera's own (0: pinhole)
    double focus_distance = 0;      // 0: the camera's own, else the distance to the scene centre
};

} // namespace clppm

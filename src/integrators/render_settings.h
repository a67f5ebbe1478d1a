// What one render is asked to do, independent of how the command line spelled it.
#pragma once
#include <cstdint>

#include "scene/scene_settings.h"

namespace clppm {

enum class Integrator { PPM, SPPM, PPPM, PT, VCM, BPT }; // --integrator ppm|sppm|pppm|pt|vcm|bpt
enum class DirectLighting { Photons, Sample };           // --direct photons|sample
enum class PixelFilter { Box, Tent };                    // --filter box|tent

const char* to_string(Integrator integrator); // "ppm", "pt"
const char* to_string(DirectLighting direct); // "photons", "sample"
const char* to_string(PixelFilter filter);    // "box", "tent"

// The scene's part (camera, resolution, lens, path length) is the SceneSettings base.
struct RenderSettings : SceneSettings {
    Integrator integrator = Integrator::PPM;
    DirectLighting direct = DirectLighting::Sample;
    unsigned spp = 1;          // hit points (PPM) per pixel
    uint64_t photons = 200000; // photons per pass (M)
    double alpha = 0.7;
    double radius = 0; // initial radius in world units; 0: heuristic
    uint64_t seed = 1;
    PixelFilter filter = PixelFilter::Box;
    // VCM and BPT: one technique alone (VCM_MODE_* of kernels/vcm_mis.h), for the tests that
    // compare the techniques; -1: the integrator's own.
    int vcm_techniques = -1;
};

} // namespace clppm

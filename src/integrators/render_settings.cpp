#include "integrators/render_settings.h"

namespace clppm {

const char* to_string(Integrator integrator) {
    switch (integrator) {
    case Integrator::PPM: return "ppm";
    case Integrator::SPPM: return "sppm";
    case Integrator::PPPM: return "pppm";
    case Integrator::PT: return "pt";
    case Integrator::VCM: return "vcm";
    case Integrator::BPT: return "bpt";
    }
    return "?";
}

const char* to_string(PixelFilter filter) {
    switch (filter) {
    case PixelFilter::Box: return "box";
    case PixelFilter::Tent: return "tent";
    }
    return "?";
}

const char* to_string(DirectLighting direct) {
    switch (direct) {
    case DirectLighting::Photons: return "photons";
    case DirectLighting::Sample: return "sample";
    }
    return "?";
}

} // namespace clppm

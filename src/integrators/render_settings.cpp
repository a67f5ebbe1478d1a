#include "integrators/render_settings.h"

namespace clppm {

const char* to_string(PixelFilter filter) {
    switch (filter) {
    case PixelFilter::Box: return "box";
    case PixelFilter::Tent: return "tent";
    }
    return "?";
}

const char* to_string(Sampler sampler) {
    switch (sampler) {
    case Sampler::Sobol: return "sobol";
    case Sampler::ZSobol: return "zsobol";
    case Sampler::Independent: return "independent";
    }
    return "?";
}

const char* to_string(DiscCoverage coverage) {
    switch (coverage) {
    case DiscCoverage::Auto: return "auto";
    case DiscCoverage::On: return "on";
    case DiscCoverage::Off: return "off";
    }
    return "?";
}

bool disc_coverage_wanted(DiscCoverage mode, uint64_t hitpoints, uint64_t photons) {
    if (mode != DiscCoverage::Auto) return mode == DiscCoverage::On;
    return hitpoints <= 2 * photons;
}

const char* to_string(DirectLighting direct) {
    switch (direct) {
    case DirectLighting::Photons: return "photons";
    case DirectLighting::Sample: return "sample";
    }
    return "?";
}

} // namespace clppm

#include "integrators/render_settings.h"

namespace clppm {

bool disc_coverage_wanted(DiscCoverage mode, uint64_t hitpoints, uint64_t photons) {
    if (mode != DiscCoverage::Auto) return mode == DiscCoverage::On;
    return hitpoints <= 2 * photons;
}

} // namespace clppm

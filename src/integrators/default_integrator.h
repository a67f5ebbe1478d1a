// The integrator a render gets when --integrator is not given (or is "auto"), chosen by
// measurement (bench/default_integrator.sh, bench/visual_importance.sh, bench/RESULTS.md): VCM
// where glass or smooth metal casts caustics of the scene's own lights (SPPM where VCM cannot
// render the view: an orthographic camera, --filter tent); SPPM where those lights
// reach almost nothing the camera sees directly (light through a gap; with visual importance when
// a directional light's photons cover the scene's bounding disc); the path tracer everywhere else,
// and for a scene lit only by an environment.
#pragma once
#include <string>

#include "integrators/render_settings.h"
#include "scene/scene.h"

namespace clppm {

// Photons per pass in a scene with participating media where --photons is not given: a photon is
// stored at each collision there (five per photon in the fogged Cornell boxes), so a pass of the
// surfaces' 200000 stores a million, whose sort left SPPM 5.6 times Mitsuba's CPU time to equal
// error in the fog box; 50000 did better, and 10000 (more passes, whose radii shrink) better still,
// on the fog box and the volumetric caustic at 64 x 64 and 128 x 128 (bench/RESULTS.md, "Photons
// in participating media" and "Nested media, and photons per pass in media").
constexpr uint64_t kMediaPhotonsPerPass = 10000;

struct IntegratorChoice {
    std::string integrator;         // a row of integrators/integrator_table.h
    std::string reason;             // for the note: why this one
    bool visual_importance = false; // SPPM's photons from Markov chains (integrators/photon_chains.h)
};

// Below this fraction of light samples reaching their light from what the camera sees
// (integrators/light_reach.h), light comes through a gap: SPPM. Measured (bench/RESULTS.md, "Light
// through a gap"): the path tracer is best in the doorway (24% reach), SPPM with visual importance
// in the skylit room (1%); the threshold is their midpoint on a log scale.
constexpr double kGapReach = 0.05;

// `scene` after apply_environment; settings for the camera; chains_allowed: visual importance may
// be chosen (one device, one process).
IntegratorChoice default_integrator(const Scene& scene, const RenderSettings& settings, bool chains_allowed);

// The rule above in a line, for --help.
extern const char* const kDefaultIntegratorRule;

} // namespace clppm

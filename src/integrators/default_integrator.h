// The integrator a render gets when --integrator is not given (or is "auto"), chosen by
// measurement (bench/default_integrator.sh, bench/RESULTS.md "The default integrator"): SPPM for a
// scene with lights of its own (emissive surfaces, punctual lights), the path tracer for a scene
// lit only by an environment (the default white one, --env or --env-color), where photons from the
// sky mostly light what light samples already light and the path tracer is far ahead.
#pragma once
#include <string>

#include "integrators/render_settings.h"
#include "scene/scene.h"

namespace clppm {

struct IntegratorChoice {
    std::string integrator; // a row of integrators/integrator_table.h
    std::string reason;     // for the note: why this one
};

// `scene` after apply_environment.
IntegratorChoice default_integrator(const Scene& scene);

// The rule above in a line, for --help.
extern const char* const kDefaultIntegratorRule;

} // namespace clppm

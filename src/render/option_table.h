// The options of a render, one table (name, value, range, default, help, and what it sets in
// RenderOptions) that every front end reads: the command line builds its parser and --help from
// it, the Python module applies its keyword arguments through it, so that both accept the same
// values with the same defaults and refuse the rest with the same one-line messages.
#pragma once
#include <string>
#include <vector>

#include "render/option_values.h"
#include "render/render_options.h"

namespace clppm {

// What an option is to a render's result: the one place that says it. Every list of options that
// must agree derives from this column (render/render_options.cpp: what every MPI process must
// share; render/job_fingerprint.cpp: what a checkpoint continues only under; the Python module's
// settings), and tests/option_roles_test.cpp renders with each option changed to catch an option
// that changes the image and is not marked so.
enum class OptionRole {
    Local, // how this process runs and reports: outputs, previews, verbosity, devices, viewers
    Run,   // when passes stop and what is estimated: every process must agree; a checkpoint may go on
           // under another
    Image, // the image itself: every process must agree, and a checkpoint goes on only under the same
};

struct RenderOptionSpec {
    const char* group;      // --help's section: "Output", "Integrator", ...
    const char* name;       // "--alpha"
    const char* short_name; // "-o", or nullptr
    const char* metavar;    // "A"; nullptr for a flag
    const char* help;
    const char* range; // nullptr when any value goes; the tail of every message: "--alpha 1.5: must be <range>"
    const char* default_text;
    void (*apply)(RenderOptions& options, const OptionArg& arg);
    OptionRole role;
    Json (*value)(const RenderOptions& options); // the option's value as set; nullptr for Local
};

// The value of every option of `role` in `options`, by name (--help's order).
Json option_values(const RenderOptions& options, OptionRole role);

// Every render option, in --help's order.
const std::vector<RenderOptionSpec>& render_option_table();

// The spec named "--name" or "-o"; nullptr when there is none.
const RenderOptionSpec* find_render_option(const std::string& name);

// Applies one occurrence: `shown` is the name as typed, `value` "" for a flag. Throws Error with
// the one-line message.
void apply_render_option(RenderOptions& options, const RenderOptionSpec& spec, const std::string& shown,
                         const std::string& value);

// The checks between options, once all are applied ("--passes 0: unlimited passes need --time",
// "--error-bound: needs --target-error", ...). Throws Error.
void check_render_options(const RenderOptions& options);

} // namespace clppm

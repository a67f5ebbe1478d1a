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

struct RenderOptionSpec {
    const char* group;      // --help's section: "Output", "Integrator", ...
    const char* name;       // "--alpha"
    const char* short_name; // "-o", or nullptr
    const char* metavar;    // "A"; nullptr for a flag
    const char* help;
    const char* range; // nullptr when any value goes; the tail of every message: "--alpha 1.5: must be <range>"
    const char* default_text;
    void (*apply)(RenderOptions& options, const OptionArg& arg);
};

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

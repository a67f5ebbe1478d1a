// The clppm command line: the render options of render/option_table.h (parsed and range-checked
// there, so that the renderer only ever sees valid values, with one-line errors naming the option
// and its range) and the command line's own flags.
#pragma once
#include <string>
#include <vector>

#include "render/render_options.h"

namespace clppm {

struct CommandLine {
    RenderOptions render; // output defaults to clppm.exr here
    bool list_devices = false;
    bool help = false;    // -h/--help: print usage() and exit
    bool version = false; // --version: print the version and exit
};

// Parses argv[1..argc-1]. Both "--opt value" and "--opt=value" are accepted. Parsing stops at
// -h/--help or --version (the flag is set, the rest is ignored). Throws clppm::Error with one line
// such as "--alpha 1.5: must be in (0, 1]" or "unknown option --foo (see --help)".
CommandLine parse_options(int argc, char** argv);

// The same on already split arguments (without the program name); used by the tests.
CommandLine parse_options(const std::vector<std::string>& args);

// Usage text listing every option with its range and default.
std::string usage();

} // namespace clppm

// `clppm compare IMAGE.exr REFERENCE.exr [--diff OUT.png] [--box K]`: the metrics of
// io/image_compare.h as JSON on stdout, parsed with CLI11 like the render command line.
#pragma once
#include <string>

namespace clppm {

// The compare command's help text (clppm compare --help).
std::string compare_usage();

// args: what follows "compare"; returns the exit status; bad arguments throw clppm::Error with one
// line naming the option.
int compare_command(int argc, char** argv);

} // namespace clppm

// One render as the clppm command runs it: load, upload, build kernels, prepare (or resume),
// refinement passes until a limit or an interrupt, with progressive images and checkpoints along
// the way, then the final images and statistics.
#pragma once
#include "cli/options.h"

namespace clppm {

// Returns the process exit status: 0, or interrupted_exit_status() after Ctrl-C/SIGTERM.
int render_session(const Options& options);

} // namespace clppm

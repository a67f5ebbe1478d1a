// `clppm [render] ...`: the render loop (render/render_loop.h) with the observers the options ask
// for, Ctrl-C and SIGTERM turned into a stop request, and the exit status: 0, 1 when the image has
// pixels that are not finite or negative, 128 + the signal when interrupted.
#pragma once
#include "render/render_options.h"

namespace clppm {

int render_command(const RenderOptions& options);

} // namespace clppm

// The observers a render's options ask for, made before the render is set up so that a live view
// address that cannot be bound or a viewer that is not there fails before any work: the progress
// line, --progressive-output, --display-server, --serve and --checkpoint (rank 0 alone: it speaks,
// serves and writes), and the MPI statistics (every rank: they are a collective).
#pragma once
#include <memory>
#include <vector>

#include "render/render_log.h"
#include "render/render_observer.h"
#include "render/render_options.h"

namespace clppm {

std::vector<std::unique_ptr<RenderObserver>> standard_observers(const RenderOptions& options, RenderLog& log);

} // namespace clppm

#include "cli/render_command.h"

#include <csignal>

#include "cli/interrupt.h"
#include "device/cluster.h"
#include "render/render_job.h"
#include "render/render_loop.h"
#include "render/standard_observers.h"

namespace clppm {

int render_command(const RenderOptions& options) {
    install_interrupt_handlers();
    set_interrupt_context(cluster().size(), cluster().rank());
    RenderLog log(options.quiet);
    auto observers = standard_observers(options, log);
    RenderJob job(options, log);
    RenderLoop loop(job, std::move(observers));
    const RenderEnd end = loop.run();
    if (end.interrupted) return interrupted_exit_status(interrupt_signal() ? interrupt_signal() : SIGINT);
    return end.defective_pixels ? 1 : 0;
}

} // namespace clppm

// Ctrl-C and SIGTERM during a render: the first asks the render to stop (the pass in progress is
// abandoned at its next photon batch, util/cancellation.h) and save its last complete pass; a second one exits at once (files already written stay whole: every
// write is a rename of a complete temporary file).
#pragma once

namespace clppm {

void install_interrupt_handlers();

// Several processes (device/cluster.h): rank 0 says why the job stops, the others say nothing.
void set_interrupt_context(int ranks, int rank);

// 0 while no stop was requested, else the signal number (SIGINT or SIGTERM).
int interrupt_signal();

// The exit status of a render stopped by `sig`: 128 + sig (130 for SIGINT, 143 for SIGTERM).
inline int interrupted_exit_status(int sig) { return 128 + sig; }

} // namespace clppm

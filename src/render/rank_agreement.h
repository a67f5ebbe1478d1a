// The processes of an MPI job (device/cluster.h) must render the same thing: mpirun starts one
// command everywhere, but a hand-made launch (mpirun -np 1 clppm --width 32 : -np 1 clppm --width
// 64) or a scene file that differs between machines would have them run different passes and
// wait for each other in collectives that never match, or crash. Checked first thing, and again
// once the scene is loaded; every rank then throws ErrorOnEveryRank naming what differs, and
// rank 0 says it.
#pragma once
#include <cstdint>
#include <string>

#include "io/stats_json.h"

namespace clppm {

// `what` (JSON: an object of option names and values) is the same on every rank, or every rank
// throws ErrorOnEveryRank: "the processes were not started alike: --width 32 on rank 0, 64 on
// rank 1". A collective: every rank calls it at the same point.
void require_ranks_agree(const Json& what);

} // namespace clppm

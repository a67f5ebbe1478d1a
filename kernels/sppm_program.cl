/* sppm_program.cl: the kernels of a stochastic or probabilistic PPM render (EYE_SLOTS 1). */
#include "eye_pass.cl"
#include "photon_trace.cl"
#ifdef PHOTON_VISUAL_IMPORTANCE
#include "photon_chain.cl"
#endif
#include "hash_grid.cl"
#include "gather.cl"
#include "disc_coverage.cl"
#include "direct_light.cl"
#include "ppm_update.cl"
#include "sppm.cl"
#include "error_estimate.cl"
#if HAS_MEDIUM
#include "beam.cl"
#endif

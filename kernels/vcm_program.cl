/* vcm_program.cl: the kernels of a vertex connection and merging or bidirectional path tracing
 * render: light and camera sub-paths, the hashed grid over light vertices, the film. */
#define GRID_ELEM LightVertex
#include "hash_grid.cl"
#include "vcm.cl"
#include "mean_film.cl"
#include "pt_error.cl"

#!/bin/bash
# --sampler zsobol against --sampler sobol at equal passes (the layout costs nothing per pass, so
# equal passes is equal time): bench/ab_error.sh with A = sobol, B = zsobol, PASSES pass counts and
# seeds 11 on; the relative MSE ratio and the box-4 one are the measures bench/RESULTS.md quotes.
#   bench/zsobol.sh [BUILD_DIR]
#   env: SCENES="cornell_diffuse tests/data/env_outdoor.gltf", PASSES="64 256 1024", ROUNDS=4,
#        SIZE=128, REF_PASSES=40000, REF_DIR=/tmp/clppm-sampler-refs (shared with bench/ab_error.sh)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
A_LABEL=sobol A_OPTS="--sampler sobol" B_LABEL=zsobol B_OPTS="--sampler zsobol" INTEGRATOR=pt FIRST_SEED=11 \
  SCENES=${SCENES:-"cornell_diffuse $here/../tests/data/env_outdoor.gltf"} PASSES=${PASSES:-"64 256 1024"} \
  ROUNDS=${ROUNDS:-4} exec "$here/ab_error.sh" "$@"

#!/bin/bash
# The path tracer's Sobol' points against independent random numbers at equal time (issue 36):
# bench/ab_error.sh with A = --sampler independent, B = --sampler sobol. For each scene a reference
# (the path tracer, independent numbers, another seed, REF_PASSES passes; cached under REF_DIR),
# then ROUNDS alternating runs of each sampler for SECONDS_EACH each, a new seed every round.
#   bench/sampler.sh [BUILD_DIR]   (env: SCENES="cornell_diffuse ...", SECONDS_EACH=10, ROUNDS=3,
#                                   REF_PASSES=40000, SIZE=128, REF_DIR=/tmp/clppm-sampler-refs)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
A_LABEL=independent A_OPTS="--sampler independent" B_LABEL=sobol B_OPTS="--sampler sobol" INTEGRATOR=pt \
  exec "$here/ab_error.sh" "$@"

/* photon_chain.cl: photon tracing guided by visual importance (Hachisuka and Jensen 2009, "Robust
 * adaptive photon tracing using photon path visibility"), built with -DPHOTON_VISUAL_IMPORTANCE.
 *
 * A photon path is a function of its numbers u in primary sample space; V(u) = 1 when it stores a
 * photon some hit point may gather (photon_trace.cl, PHOTON_SEEN). Each photon index of a pass
 * keeps a Markov chain whose stationary density is proportional to V, and each pass advances it by
 * one step of a replica exchange with a uniform chain (Sec. 4.1-4.2):
 *   1. a uniform path u ~ U: if V(u) = 1 the chain swaps it in (the exchange's acceptance is
 *      V(u) / V(state) = V(u)), and the count V_c of visible uniform paths grows;
 *   2. otherwise a mutation u' = state + d (2 xi - 1) of every number (wrapped to [0, 1)), which
 *      the chain accepts when V(u') = 1 (Metropolis, symmetric proposal);
 *   3. otherwise the chain stays, and its state's path is traced again.
 * Exactly one path per chain with a state deposits its photons; the others stored none (V = 0).
 * The flux of the photons is that of an ordinary photon (f(u) / p_U, p_U = 1), and the image's
 * photon count is N_states N_U / V_c (Eq. 6: the integral of V is V_c / N_U), which the host
 * passes to the film (PhotonChains::effective_emitted).
 * The mutation's size d adapts by the Robbins-Monro rule d += (A - 0.234) / t towards an
 * acceptance of 0.234 (Sec. 4.3, after Andrieu and Thoms 2008). The numbers past the first
 * PHOTON_CHAIN_DIMS come from a stream whose seed the state keeps; a mutation keeps it or draws a
 * new one with even odds, a symmetric choice. A state's photons (every hit the path would store,
 * seen or not, up to PHOTON_CHAIN_CACHE) are kept, so that step 3 stores those now seen without
 * tracing the path again.
 *
 * A pass of M uniform paths runs ceil(M / PHOTON_CHAIN_STEPS) chains of PHOTON_CHAIN_STEPS steps
 * each (kernels/shared_types.h): fewer chains with longer runs find their first states sooner
 * where few paths are visible. Chains are read from chains_in and written to chains_out, so that a
 * batch traced again after its photons overflowed (BatchedTrace) takes the same steps. */
#ifndef CLPPM_PHOTON_CHAIN_CL
#define CLPPM_PHOTON_CHAIN_CL

#include "portability.h"
#include "photon_trace.cl"
#include "visibility_mark.cl"

/* Traces the path of numbers u (and the stream seeded by tail after them); *n_rec counts the
 * photons it records in rec. */
uint chain_path(SCENE_PARAMS, const float* u, uint2 tail, const PassWavelength* pw, uint skip_direct,
                __global Photon* photons, uint capacity, volatile __global uint* counter SEEN_PARAMS) {
    Rng r = rng_make(as_ulong(tail), 0, 0, RNG_PHOTON_TAIL);
    r.pss = u;
    r.pss_next = 0;
    r.pss_dims = PHOTON_CHAIN_DIMS;
    *n_rec = 0;
    return photon_path(SCENE_ARGS, &r, pw, skip_direct, photons, capacity, counter SEEN_ARGS);
}

/* x wrapped into [0, 1) */
float wrap_unit(float x) {
    x -= floor(x);
    return x < 1.0f ? x : 0.0f;
}

#define CHAIN_TARGET_ACCEPTANCE 0.234f
#define CHAIN_MIN_STEP (1.0f / 65536.0f)
/* A state's photons are kept unless the pass's wavelength changes them (dispersion.cl). */
#define CHAIN_CACHE (!HAS_DISPERSION)

/* The path just traced (rec, n_rec) becomes the state: its photons into the chain's cache. */
void chain_keep(PhotonChain* ch, const Photon* rec, uint n_rec, __global Photon* cache) {
    if (!CHAIN_CACHE || n_rec > PHOTON_CHAIN_CACHE) {
        ch->cached = PHOTON_CHAIN_UNCACHED;
        return;
    }
    for (uint j = 0; j < n_rec; ++j) cache[j] = rec[j];
    ch->cached = n_rec;
}

/* One step of chain ch (Sec. 4.2), drawing from rng; cache holds its state's photons. */
void chain_step(SCENE_PARAMS, PhotonChain* ch, Rng* rng, const PassWavelength* pw, uint skip_direct,
                __global Photon* photons, uint capacity, volatile __global uint* counter SEEN_PARAMS,
                __global Photon* cache, uint* counts) {
    /* 1. The uniform chain's path. */
    float u[PHOTON_CHAIN_DIMS];
    for (int k = 0; k < PHOTON_CHAIN_DIMS; ++k) u[k] = rng_float(rng);
    const uint2 tail = (uint2)(rng_next(rng), rng_next(rng));
    if (chain_path(SCENE_ARGS, u, tail, pw, skip_direct, photons, capacity, counter SEEN_ARGS) > 0) {
        ++counts[CHAIN_UNIFORM_VISIBLE];
        for (int k = 0; k < PHOTON_CHAIN_DIMS; ++k) ch->u[k] = u[k];
        ch->tail[0] = tail.x;
        ch->tail[1] = tail.y;
        chain_keep(ch, rec, *n_rec, cache);
        if (!(ch->step > 0.0f)) ch->step = 1.0f; /* the first state: adaptation starts from d = 1 */
    } else if (ch->step > 0.0f) {
        /* 2. A mutation of the state. A new tail is drawn afresh: the uniform path's, rejected as
         * invisible, would make the proposal depend on that rejection, and the chain would drift
         * towards invisible states (delayed rejection, Tierney and Mira 1999). */
        float v[PHOTON_CHAIN_DIMS];
        for (int k = 0; k < PHOTON_CHAIN_DIMS; ++k) {
            v[k] = wrap_unit(ch->u[k] + ch->step * (2.0f * rng_float(rng) - 1.0f));
            u[k] = ch->u[k];
        }
        const uint2 state_tail = (uint2)(ch->tail[0], ch->tail[1]);
        const uint2 fresh_tail = (uint2)(rng_next(rng), rng_next(rng));
        const uint2 new_tail = rng_float(rng) < 0.5f ? state_tail : fresh_tail;
        ch->mutations += 1;
        ++counts[CHAIN_MUTATIONS];
        const bool accepted =
            chain_path(SCENE_ARGS, v, new_tail, pw, skip_direct, photons, capacity, counter SEEN_ARGS) > 0;
        /* Robbins-Monro on log d, gain 2 / sqrt(t): d falls from 1 to a few thousandths within
         * a hundred rejections, and adapts ever less (diminishing adaptation). */
        const float a = accepted ? 1.0f : 0.0f;
        ch->step = clamp(ch->step * exp((a - CHAIN_TARGET_ACCEPTANCE) * 2.0f * rsqrt((float)ch->mutations)),
                         CHAIN_MIN_STEP, 1.0f);
        if (accepted) {
            ++counts[CHAIN_ACCEPTED];
            for (int k = 0; k < PHOTON_CHAIN_DIMS; ++k) ch->u[k] = v[k];
            ch->tail[0] = new_tail.x;
            ch->tail[1] = new_tail.y;
            chain_keep(ch, rec, *n_rec, cache);
        } else if (ch->cached != PHOTON_CHAIN_UNCACHED) {
            /* 3. The chain stays: its state's photons once more, those where hit points may
             * gather now (the marks only grow: the same photons a trace would store). */
            for (uint j = 0; j < ch->cached; ++j) {
                const Photon ph = cache[j];
                if (PHOTON_SEEN((float3)(ph.pos[0], ph.pos[1], ph.pos[2]))) put_photon(photons, capacity, counter, &ph);
            }
        } else {
            chain_path(SCENE_ARGS, u, state_tail, pw, skip_direct, photons, capacity, counter SEEN_ARGS);
        }
    }
    if (ch->step > 0.0f) ++counts[CHAIN_STATES];
}

/* Chains [first_chain, first_chain + num_chains) of the pass's, each taking PHOTON_CHAIN_STEPS
 * steps of the pass's num_photons (the last chain fewer): one uniform path per step. Each chain's
 * cached photons move from cache_in to cache_out with it. */
__kernel SCALAR_WORK_ITEMS void photon_chain_trace(SCENE_PARAMS, ulong seed, ulong pass, uint first_chain,
                                                   uint num_chains, uint skip_direct, __global Photon* photons,
                                                   uint capacity, volatile __global uint* counter SEEN_KERNEL_PARAMS,
                                                   __global const PhotonChain* chains_in,
                                                   __global PhotonChain* chains_out, __global const Photon* cache_in,
                                                   __global Photon* cache_out, volatile __global uint* counts,
                                                   uint num_photons) {
    uint i = get_global_id(0);
    if (i >= num_chains || info->num_lights == 0) return;
    const uint c = first_chain + i;
    PhotonChain ch = chains_in[c];
    __global Photon* cache = cache_out + (size_t)c * PHOTON_CHAIN_CACHE;
    if (ch.step > 0.0f && ch.cached != PHOTON_CHAIN_UNCACHED)
        for (uint j = 0; j < ch.cached; ++j) cache[j] = cache_in[(size_t)c * PHOTON_CHAIN_CACHE + j];
    Rng rng = rng_make(seed, pass, c, RNG_PHOTON);
    const PassWavelength pw = pass_wavelength(seed, pass);
    Photon rec[PHOTON_CHAIN_CACHE];
    uint recorded = 0, *n_rec = &recorded;
    uint n[CHAIN_COUNTS] = {0, 0, 0, 0};
    const uint first_step = c * PHOTON_CHAIN_STEPS;
    const uint steps = min((uint)PHOTON_CHAIN_STEPS, num_photons - first_step);
    for (uint s = 0; s < steps; ++s)
        chain_step(SCENE_ARGS, &ch, &rng, &pw, skip_direct, photons, capacity, counter SEEN_ARGS, cache, n);
    for (int k = 0; k < CHAIN_COUNTS; ++k)
        if (n[k]) atomic_add(&counts[k], n[k]);
    chains_out[c] = ch;
}

#endif

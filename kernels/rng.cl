/* rng.cl: PCG32 (O'Neill 2014) with streams derived by SplitMix64 from (seed, pass, index, purpose),
 * so every pass and every work item draws from its own stream and the image does not depend on
 * the work-group size or the order work items run in. tests/rng_test.cpp holds the host
 * reference. */
#ifndef CLPPM_RNG_CL
#define CLPPM_RNG_CL

typedef struct {
    ulong state;
    ulong inc;
#ifdef PHOTON_VISUAL_IMPORTANCE
    /* A Markov chain's photon path (kernels/photon_chain.cl): its first pss_dims numbers come from
     * pss, the rest from the stream. */
    const float* pss;
    uint pss_next, pss_dims;
#endif
} Rng;

ulong splitmix64(ulong x) {
    x += 0x9E3779B97F4A7C15UL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9UL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBUL;
    return x ^ (x >> 31);
}

uint rng_next(Rng* r) {
    ulong old = r->state;
    r->state = old * 6364136223846793005UL + r->inc;
    uint xorshifted = (uint)(((old >> 18) ^ old) >> 27);
    uint rot = (uint)(old >> 59);
    return (xorshifted >> rot) | (xorshifted << ((0u - rot) & 31u));
}

/* Uniform in [0, 1): 24 random bits, exactly representable. */
float rng_float(Rng* r) {
#ifdef PHOTON_VISUAL_IMPORTANCE
    if (r->pss_next < r->pss_dims) return r->pss[r->pss_next++];
#endif
    return (float)(rng_next(r) >> 8) * (1.0f / 16777216.0f);
}

/* purpose separates the streams of different kernels that share (pass, index). */
Rng rng_make(ulong seed, ulong pass, ulong index, uint purpose) {
    Rng r;
    ulong a = splitmix64(seed ^ splitmix64(pass * 0x100000001B3UL + purpose));
    ulong b = splitmix64(a ^ splitmix64(index));
    r.state = 0;
    r.inc = (b << 1) | 1UL;
#ifdef PHOTON_VISUAL_IMPORTANCE
    r.pss = 0;
    r.pss_next = r.pss_dims = 0;
#endif
    rng_next(&r);
    r.state += splitmix64(b);
    rng_next(&r);
    return r;
}

#define RNG_EYE 1u
#define RNG_PHOTON 2u
#define RNG_DIRECT 3u
#define RNG_PATH 4u
#define RNG_VCM_LIGHT 5u
#define RNG_VCM_CAMERA 6u
#define RNG_PHOTON_TAIL 7u
#define RNG_DISC_COVERAGE 8u

#endif

/* sobol.cl: Owen-scrambled Sobol' points for the path tracer (issue 36). Each draw of a path
 * (the pixel position, the lens, and at every bounce the light's pick and point, the BSDF's lobe
 * and direction, Russian roulette) is its own "dimension" d. Across the passes j = 0, 1, 2, ... a
 * pixel's draws of dimension d are the points of one randomised sequence:
 *
 *   2-D draws: the first two Sobol' dimensions (van der Corput, and the Pascal matrix) of a
 *              shuffled index, a (0,2)-sequence in base 2: every 2^m consecutive passes starting
 *              at a multiple of 2^m put one point in each of the 2^m elementary intervals of any
 *              shape (a (0,m,2)-net);
 *   1-D draws: van der Corput of a shuffled index, stratified the same way.
 *
 * Randomisation, as Burley 2020 ("Practical Hash-based Owen Scrambling", JCGT 9(4), Sec. 4 and 5)
 * and pbrt-v4's padded samplers (src/pbrt/util/lowdiscrepancy.h, FastOwenScrambler):
 * - the index j is shuffled per (pixel, dimension) by a nested uniform scramble of its reversed
 *   bits, which maps every aligned block of 2^m indices onto an aligned block; this is what makes
 *   dimensions independent of one another (padding), and keeps every prefix of 2^m passes a net;
 * - each coordinate is Owen-scrambled by a hash whose every bit depends only on the bits above it
 *   (Laine and Karras 2011, with the constants of pbrt-v4 after Vegdahl), so each point is
 *   uniform on [0,1)^2 and the estimate stays unbiased.
 * Draws from the SOBOL_QMC_DRAWS-th on are independent numbers (below).
 * Seeds come from (seed, pixel, dimension) only, so a pass's samples do not depend on the device,
 * the work-group size or the passes other devices ran. tests/sobol_test.cpp holds the host
 * reference. The index is the pass number modulo 2^32. */
#ifndef CLPPM_SOBOL_CL
#define CLPPM_SOBOL_CL

#include "rng.cl"

/* Bit reversal, on two words at once: sobol_2d's two coordinates share every step (one vector op
 * each on SSE/AVX, where the scalar chains ran one after the other); one word takes the first
 * lane. */
uint2 reverse_bits32x2(uint2 v) {
    v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    v = ((v >> 4) & 0x0F0F0F0Fu) | ((v & 0x0F0F0F0Fu) << 4);
    v = ((v >> 8) & 0x00FF00FFu) | ((v & 0x00FF00FFu) << 8);
    return (v >> 16) | (v << 16);
}

uint reverse_bits32(uint v) { return reverse_bits32x2((uint2)(v)).x; }

/* A random permutation of 32-bit words in which output bit k depends only on input bits 0..k:
 * applied to reversed bits it is a nested uniform (Owen) scramble. */
uint2 owen_hash_x2(uint2 v, uint2 seed) {
    v ^= v * 0x3d20adeau;
    v += seed;
    v *= (seed >> 16) | 1u;
    v ^= v * 0x05526c56u;
    v ^= v * 0x53a22864u;
    return v;
}

uint owen_hash(uint v, uint seed) { return owen_hash_x2((uint2)(v), (uint2)(seed)).x; }

/* The second Sobol' dimension before its bits are reversed: output bit k is the XOR of the index
 * bits j whose binary digits contain k's (the Pascal matrix mod 2, C(j, k) odd by Lucas'
 * theorem), a superset-sum over the five bits of the bit position. */
uint sobol_pascal_reversed(uint i) {
    i ^= (i >> 1) & 0x55555555u;
    i ^= (i >> 2) & 0x33333333u;
    i ^= (i >> 4) & 0x0F0F0F0Fu;
    i ^= (i >> 8) & 0x00FF00FFu;
    i ^= (i >> 16) & 0x0000FFFFu;
    return i;
}

/* 24 bits of a 32-bit fixed-point fraction: exactly representable, below 1. */
float sobol_to_float(uint x) { return (float)(x >> 8) * (1.0f / 16777216.0f); }

/* A 32-bit integer hash (Wellons' lowbias32): vectorises on CPUs without 64-bit multiplies. */
uint2 hash32_x2(uint2 x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    return x ^ (x >> 16);
}

uint hash32(uint x) { return hash32_x2((uint2)(x)).x; }

typedef struct {
    uint seed;           /* (render seed, pixel) */
    uint index_reversed; /* the pass number, bits reversed */
    uint dim;            /* the next draw's dimension */
} Sobol;

Sobol sobol_make(ulong seed, uint pixel, ulong pass) {
    Sobol s;
    s.seed = (uint)splitmix64(seed ^ splitmix64((ulong)pixel + 0x632BE59BD9B4E019UL));
    s.index_reversed = reverse_bits32((uint)pass);
    s.dim = 0;
    return s;
}

/* Bits of x at the even positions of a 64-bit word: x's and y's interleaved are the Morton (Z)
 * order of a pixel, in which every aligned 2^k x 2^k block of pixels is a run of 4^k codes. */
ulong morton_spread(uint x) {
    ulong v = x;
    v = (v | (v << 16)) & 0x0000FFFF0000FFFFUL;
    v = (v | (v << 8)) & 0x00FF00FF00FF00FFUL;
    v = (v | (v << 4)) & 0x0F0F0F0F0F0F0F0FUL;
    v = (v | (v << 2)) & 0x3333333333333333UL;
    return (v | (v << 1)) & 0x5555555555555555UL;
}
/* The screen-space layout (`--sampler zsobol`; pbrt-v4's ZSobolSampler, after Ahmed and Wonka
 * 2020, "Screen-space blue-noise diffusion of Monte Carlo sampling error via hierarchical ordering
 * of pixels"). For a render planned at 2^L passes, pass j of pixel (x, y) draws point
 * I = morton(x, y) 2^L + j of one sequence that all pixels share; sobol_shuffled_index's nested
 * scramble then moves every aligned block of indices as a whole. So each pixel's passes are an
 * aligned block (a net at every power-of-two count, as in the per-pixel layout), and so are the
 * 4^k 2^L points of each aligned 2^k x 2^k block of pixels: the block's mean integrates its pixels'
 * (nearly equal) integrands with 4^k times the points of one net, and the error moves to high
 * frequencies on the screen. The scramble seeds come from the render seed, the index's bits above
 * the 32 used (images of over 2^(32-L) pixels) and the generation j / 2^L (passes past the plan
 * start a new, independent sequence). x, y < 2^16 and L <= 32; tests/sobol_test.cpp holds the
 * host reference. */
Sobol sobol_make_screen(ulong seed, uint x, uint y, ulong pass, uint log2_passes) {
    const ulong morton = morton_spread(x) | (morton_spread(y) << 1);
    const ulong index = (morton << log2_passes) | (pass & ((1UL << log2_passes) - 1UL));
    const ulong key = (index >> 32) ^ ((pass >> log2_passes) * 0xD1B54A32D192ED03UL);
    Sobol s;
    s.seed = (uint)splitmix64(seed ^ splitmix64(key + 0x2545F4914F6CDD1DUL));
    s.index_reversed = reverse_bits32((uint)index);
    s.dim = 0;
    return s;
}

/* The shuffled index of dimension d (Burley 2020, Eq. 4 and Listing 5) and two coordinate seeds. */
uint sobol_shuffled_index(Sobol* s, uint2* scramble) {
    uint h = hash32(s->seed + s->dim++ * 0x9E3779B9u);
    *scramble = hash32_x2((uint2)(h) ^ (uint2)(0x85EBCA6Bu, 0xC2B2AE35u));
    return reverse_bits32(owen_hash(s->index_reversed, h));
}

/* The first SOBOL_QMC_DRAWS draws of a path are Sobol' points; later ones are independent
 * uniforms per (seed, pixel, draw, pass), two rounds of hash32 without the scrambles. In the path
 * tracer's pattern (2 camera draws, then 4 a bounce) 10 covers the camera and two bounces. Where
 * a path goes after its second bounce barely stratifies, and the points cost: on the diffuse box
 * (128x128) every draw a point took 10% more CPU a pass than 10, for 5% more error at equal time;
 * under the sky and through the doorway the two were level (bench/RESULTS.md, issue 36). */
#ifndef SOBOL_QMC_DRAWS
#define SOBOL_QMC_DRAWS 10u
#endif
uint2 sobol_plain_bits(Sobol* s) {
    uint h = hash32(s->seed + s->dim++ * 0x9E3779B9u) ^ s->index_reversed;
    return hash32_x2((uint2)(h) ^ (uint2)(0x85EBCA6Bu, 0xC2B2AE35u));
}

float sobol_1d(Sobol* s) {
    if (s->dim >= SOBOL_QMC_DRAWS) return sobol_to_float(sobol_plain_bits(s).x);
    uint2 sc;
    uint i = sobol_shuffled_index(s, &sc);
    /* van der Corput is reverse_bits32(i); its Owen scramble reverses, hashes and reverses back */
    return sobol_to_float(reverse_bits32(owen_hash(i, sc.x)));
}

float2 sobol_2d(Sobol* s) {
    if (s->dim >= SOBOL_QMC_DRAWS) return convert_float2(sobol_plain_bits(s) >> 8) * (1.0f / 16777216.0f);
    uint2 sc;
    uint i = sobol_shuffled_index(s, &sc);
    const uint2 x = reverse_bits32x2(owen_hash_x2((uint2)(i, sobol_pascal_reversed(i)), sc));
    return convert_float2(x >> 8) * (1.0f / 16777216.0f); /* sobol_to_float of each */
}

#endif

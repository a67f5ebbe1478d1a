/* sampling.cl: directions, frames and the octahedral normal encoding. */
#ifndef CLPPM_SAMPLING_CL
#define CLPPM_SAMPLING_CL

#define PI_F 3.14159265358979323846f
#define INV_PI_F 0.31830988618379067154f

float3 load3(const float* v) { return (float3)(v[0], v[1], v[2]); }
float3 load3g(__global const float* v) { return (float3)(v[0], v[1], v[2]); }
float3 load3c(__constant const float* v) { return (float3)(v[0], v[1], v[2]); }

float max3(float3 v) { return fmax(v.x, fmax(v.y, v.z)); }

float mean3(float3 v) { return (v.x + v.y + v.z) * (1.0f / 3.0f); }

/* An orthonormal basis around unit n (Duff et al. 2017, "Building an Orthonormal Basis, Revisited"). */
void make_frame(float3 n, float3* t, float3* b) {
    float sign = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (sign + n.z);
    float c = n.x * n.y * a;
    *t = (float3)(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    *b = (float3)(c, sign + n.y * n.y * a, -n.y);
}

/* (cos 2 pi u, sin 2 pi u): the point at angle 2 pi u on the unit circle. cospi and sinpi reduce
 * their argument exactly and cheaply where cos and sin of 2 pi u take PoCL's general reduction:
 * photon tracing ran 10% faster on bunny_100k with them (bench/RESULTS.md, issue 20). */
inline float2 unit_circle(float u) { return (float2)(cospi(2.0f * u), sinpi(2.0f * u)); }

/* Cosine-weighted direction about n: pdf = cos(theta) / pi (Malley's method). */
float3 sample_cosine_hemisphere(float3 n, float u1, float u2) {
    float r = sqrt(u1);
    float2 c = unit_circle(u2);
    float3 t, b;
    make_frame(n, &t, &b);
    float z = sqrt(fmax(0.0f, 1.0f - u1));
    return normalize(t * (r * c.x) + b * (r * c.y) + n * z);
}

/* Uniform direction in the cone of directions within acos(cos_max) of axis: pdf = 1/(2 pi (1 - cos_max)). */
float3 sample_cone(float3 axis, float cos_max, float u1, float u2) {
    float cos_t = 1.0f - u1 * (1.0f - cos_max);
    float sin_t = sqrt(fmax(0.0f, 1.0f - cos_t * cos_t));
    float2 c = unit_circle(u2);
    float3 t, b;
    make_frame(axis, &t, &b);
    return normalize(t * (sin_t * c.x) + b * (sin_t * c.y) + axis * cos_t);
}

/* Uniform point on a triangle: barycentrics (b1, b2) of v1 and v2 (Heitz 2019 would avoid the sqrt;
 * this square-root map is the classic one and exact enough). */
float2 sample_triangle(float u1, float u2) {
    float su = sqrt(u1);
    return (float2)(su * u2, 1.0f - su);
}

/* Octahedral encoding of a unit vector in 2x16 bits (Cigolle et al. 2014). */
uint oct_encode(float3 n) {
    float l1 = fabs(n.x) + fabs(n.y) + fabs(n.z);
    float2 p = n.xy * (1.0f / l1);
    if (n.z < 0.0f) {
        float2 s = (float2)(p.x >= 0.0f ? 1.0f : -1.0f, p.y >= 0.0f ? 1.0f : -1.0f);
        p = (1.0f - fabs(p.yx)) * s;
    }
    uint x = (uint)clamp(rint((p.x * 0.5f + 0.5f) * 65535.0f), 0.0f, 65535.0f);
    uint y = (uint)clamp(rint((p.y * 0.5f + 0.5f) * 65535.0f), 0.0f, 65535.0f);
    return x | (y << 16);
}

float3 oct_decode(uint e) {
    float2 p = (float2)((float)(e & 0xffffu), (float)(e >> 16)) * (2.0f / 65535.0f) - 1.0f;
    float3 n = (float3)(p.x, p.y, 1.0f - fabs(p.x) - fabs(p.y));
    float t = fmax(-n.z, 0.0f);
    n.x += n.x >= 0.0f ? -t : t;
    n.y += n.y >= 0.0f ? -t : t;
    return normalize(n);
}

#endif

/* fresnel.cl: a dielectric interface's exact Fresnel reflectance, mirror and refraction
 * directions, and Schlick's (1 - cos)^5, for the lobes of kernels/bsdf.cl. */
#ifndef CLPPM_FRESNEL_CL
#define CLPPM_FRESNEL_CL

/* Unpolarised Fresnel reflectance for a dielectric; cos_i > 0 on the incident side and eta the
 * relative index n_t / n_i (pbrt-v4 FrDielectric). Returns 1 under total internal reflection. */
float fresnel_dielectric(float cos_i, float eta) {
    cos_i = clamp(cos_i, 0.0f, 1.0f);
    float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0f) return 1.0f;
    float cos_t = sqrt(1.0f - sin2_t);
    float r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5f * (r_par * r_par + r_perp * r_perp);
}

float3 reflect_dir(float3 d, float3 n) { return d - 2.0f * dot(d, n) * n; }

/* Refraction of incoming direction d (pointing at the surface) through normal n (facing against
 * d), relative index eta = n_t / n_i. Valid only when fresnel_dielectric < 1. */
float3 refract_dir(float3 d, float3 n, float eta) {
    float cos_i = -dot(d, n);
    float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
    float cos_t = sqrt(fmax(0.0f, 1.0f - sin2_t));
    return normalize(d / eta + (cos_i / eta - cos_t) * n);
}

float pow5(float x) { return (x * x) * (x * x) * x; }

#endif

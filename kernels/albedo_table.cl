/* albedo_table.cl: lookups in the tabulated albedos the lobes of kernels/bsdf.cl need for energy
 * conservation (kernels/ggx_albedo.h, sheen_albedo.h, ggx_aniso_albedo.h, made by scripts/make_*.cpp):
 * one bilinear interpolation that every table shares, and the GGX layer's tables by roughness. */
#ifndef CLPPM_ALBEDO_TABLE_CL
#define CLPPM_ALBEDO_TABLE_CL

#include "ggx_albedo.h"

/* Bilinear interpolation in a table of `rows` rows of `cols` values at the fractional column x and
 * row y, each clamped to the table. */
float table_bilinear(__constant float* t, int cols, int rows, float x, float y) {
    x = clamp(x, 0.0f, (float)(cols - 1));
    y = clamp(y, 0.0f, (float)(rows - 1));
    int i = min((int)x, cols - 2), j = min((int)y, rows - 2);
    float fx = x - (float)i, fy = y - (float)j;
    __constant float* r0 = t + j * cols;
    __constant float* r1 = r0 + cols;
    float a = r0[i] + (r0[i + 1] - r0[i]) * fx, c = r1[i] + (r1[i + 1] - r1[i]) * fx;
    return a + (c - a) * fy;
}

/* Linear interpolation in a column of `rows` values at the fractional row y, clamped. */
float table_linear(__constant float* t, int rows, float y) {
    y = clamp(y, 0.0f, (float)(rows - 1));
    int j = min((int)y, rows - 2);
    float fy = y - (float)j;
    return t[j] + (t[j + 1] - t[j]) * fy;
}

/* A GGX_ALBEDO_ALPHA x GGX_ALBEDO_MU table (kernels/ggx_albedo.h) at (mu, alpha): its rows go by
 * roughness = sqrt(alpha), its columns by mu at the cells' centres. */
float ggx_table(__constant float* t, float mu, float alpha) {
    return table_bilinear(t, GGX_ALBEDO_MU, GGX_ALBEDO_ALPHA, mu * (float)GGX_ALBEDO_MU - 0.5f,
                          sqrt(alpha) * (float)(GGX_ALBEDO_ALPHA - 1));
}

/* A table's hemispherical means (one value a row) at alpha. */
float ggx_table_avg(__constant float* t, float alpha) {
    return table_linear(t, GGX_ALBEDO_ALPHA, sqrt(alpha) * (float)(GGX_ALBEDO_ALPHA - 1));
}

#endif

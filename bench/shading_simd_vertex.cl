/* shading_simd_vertex.cl: one path vertex's shading, written once for any SIMD width.
 * bench/shading_simd.cpp instantiates it as a kernel SIMD_NAME with W lanes per work item:
 *   W 1: one path per work item (float, uint), as the renderer's kernels are written;
 *   W 8 or 16: W paths per work item in floatW / uintW lanes, their scene data gathered lane by lane.
 * Each lane does the same operations in the same order, so every width computes the same numbers up
 * to the last bits of the math builtins. The work: a Lambertian surface (kernels/scene.cl
 * make_surface without its optional parts), one light sample on one of at most two emissive
 * triangles, picked in proportion to power with the number reused for the point (kernels/lights.cl
 * pick_light_reuse, sample_chosen_light), weighed by the power heuristic against the cosine lobe,
 * and a cosine-distributed bounce in Duff et al.'s frame (kernels/sampling.cl). The host checks that
 * the scene holds nothing else.
 * Macros (from the host): SIMD_W, SIMD_NAME, SIMD_TRI (its helper's name), T, UT, IT, LANES (the
 * lane offsets as UT), LD/ST (vector load/store at lane group i), G/GU (gather of a float/uint array
 * at UT indices), CVT (UT to T). */

/* The point at barycentrics (b1, b2) of triangle prim, and its unit winding normal. */
inline void SIMD_TRI(__global const float* tf, UT prim, T b1, T b2, T* x, T* y, T* z, T* nx, T* ny, T* nz) {
    const UT p12 = prim * 12u;
    const T v0x = G(tf, p12), v0y = G(tf, p12 + 1u), v0z = G(tf, p12 + 2u);
    const T e1x = G(tf, p12 + 4u), e1y = G(tf, p12 + 5u), e1z = G(tf, p12 + 6u);
    const T e2x = G(tf, p12 + 8u), e2y = G(tf, p12 + 9u), e2z = G(tf, p12 + 10u);
    *x = v0x + e1x * b1 + e2x * b2;
    *y = v0y + e1y * b1 + e2y * b2;
    *z = v0z + e1z * b1 + e2z * b2;
    const T cx = e1y * e2z - e1z * e2y, cy = e1z * e2x - e1x * e2z, cz = e1x * e2y - e1y * e2x;
    const T l = sqrt(cx * cx + cy * cy + cz * cz);
    *nx = cx / l;
    *ny = cy / l;
    *nz = cz / l;
}

__kernel void SIMD_NAME(SCENE_PARAMS, __global const float* soa, uint n, uint pass, __global float* out) {
    const uint i = get_global_id(0);
    const T t = LD(soa, i), bu = LD(soa + n, i), bv = LD(soa + 2 * n, i);
    const UT prim = LDU((__global const uint*)soa + 3 * n, i);
    const T dx = LD(soa + 4 * n, i), dy = LD(soa + 5 * n, i), dz = LD(soa + 6 * n, i);

    /* the hit point and the geometric normal, facing the ray */
    __global const float* tf = (__global const float*)tris;
    T px, py, pz, gx, gy, gz;
    SIMD_TRI(tf, prim, bu, bv, &px, &py, &pz, &gx, &gy, &gz);
    /* the interpolated shading normal and the material */
    __global const float* sf = (__global const float*)shading;
    const UT s16 = prim * 16u;
    const T b0 = 1.0f - bu - bv;
    T nx = G(sf, s16) * b0 + G(sf, s16 + 3u) * bu + G(sf, s16 + 6u) * bv;
    T ny = G(sf, s16 + 1u) * b0 + G(sf, s16 + 4u) * bu + G(sf, s16 + 7u) * bv;
    T nz = G(sf, s16 + 2u) * b0 + G(sf, s16 + 5u) * bu + G(sf, s16 + 8u) * bv;
    const T nl = sqrt(nx * nx + ny * ny + nz * nz);
    nx /= nl;
    ny /= nl;
    nz /= nl;
    const UT mat = GU((__global const uint*)sf, s16 + 15u);
    const T side = select((T)(1.0f), (T)(-1.0f), gx * dx + gy * dy + gz * dz >= 0.0f);
    gx *= side;
    gy *= side;
    gz *= side;
    nx *= side;
    ny *= side;
    nz *= side;
    __global const float* mf = (__global const float*)materials;
    const UT m0 = mat * (uint)(sizeof(Material) / sizeof(float));
    const T fr = G(mf, m0) * INV_PI_F, fg = G(mf, m0 + 1u) * INV_PI_F, fb = G(mf, m0 + 2u) * INV_PI_F;
    const T ler = G(mf, m0 + 4u), leg = G(mf, m0 + 5u), leb = G(mf, m0 + 6u);

    /* four uniforms per lane from (pixel, pass) */
    UT h = (UT)(i * SIMD_W) + LANES;
    h = h * 0x9E3779B9u ^ (UT)(pass * 0x85EBCA6Bu);
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    const T u0 = CVT(h >> 8) * 0x1.0p-24f;
    h = h * 0x9E3779B9u ^ (h >> 16);
    const T u1 = CVT(h >> 8) * 0x1.0p-24f;
    h = h * 0x9E3779B9u ^ (h >> 16);
    const T u2 = CVT(h >> 8) * 0x1.0p-24f;
    h = h * 0x9E3779B9u ^ (h >> 16);
    const T u3 = CVT(h >> 8) * 0x1.0p-24f;

    /* the light: u0 picks one of the (at most two) lights and, rescaled, places the point */
    const float c1 = light_cdf[1];
    const IT second = u0 >= c1;
    const UT l = select((UT)(0u), (UT)(1u), second);
    const T c0 = select((T)(0.0f), (T)(c1), second), w = select((T)(c1), (T)(1.0f - c1), second);
    const T ul = fmin((u0 - c0) / w, 0.99999994f);
    __global const float* lf = (__global const float*)lights;
    const UT l20 = l * (uint)(sizeof(Light) / sizeof(float));
    const UT lp = GU((__global const uint*)lf, l20 + 1u);
    const T lpow = G(lf, l20 + 3u), larea = G(lf, l20 + 18u);
    const T lr = G(lf, l20 + 12u), lg = G(lf, l20 + 13u), lb = G(lf, l20 + 14u);
    const T su = sqrt(ul), sb1 = 1.0f - su, sb2 = u1 * su;
    T yx, yy, yz, lnx, lny, lnz;
    SIMD_TRI(tf, lp, sb1, sb2, &yx, &yy, &yz, &lnx, &lny, &lnz);
    const T ddx = yx - px, ddy = yy - py, ddz = yz - pz;
    const T d2 = ddx * ddx + ddy * ddy + ddz * ddz;
    const T len = sqrt(d2);
    const T wix = ddx / len, wiy = ddy / len, wiz = ddz / len;
    const T cos_y = -(wix * lnx + wiy * lny + wiz * lnz);
    const T cos_x = wix * nx + wiy * ny + wiz * nz;
    const T pick = lpow / info->total_power;
    /* solid-angle densities of the light sample and of the cosine lobe; the power heuristic */
    const T light_pdf = pick / larea * d2 / cos_y;
    const T bsdf_pdf = cos_x * INV_PI_F;
    const T mis = light_pdf * light_pdf / (light_pdf * light_pdf + bsdf_pdf * bsdf_pdf);
    const T k = select((T)(0.0f), cos_x * cos_y * larea / (d2 * pick) * mis, (cos_y > 0.0f) & (cos_x > 0.0f));
    const T Lr = fr * lr * k + ler, Lg = fg * lg * k + leg, Lb = fb * lb * k + leb;
    const T dist = len - 2.0f * (info->ray_eps + 4e-6f * fmax(fabs(yx), fmax(fabs(yy), fabs(yz))));

    /* the bounce: cosine-distributed about the shading normal */
    const T sgn = select((T)(-1.0f), (T)(1.0f), nz >= 0.0f);
    const T a = -1.0f / (sgn + nz), c = nx * ny * a;
    const T tx = 1.0f + sgn * nx * nx * a, ty = sgn * c, tz = -sgn * nx;
    const T bx = c, by = sgn + ny * ny * a, bz = -ny;
    const T r = sqrt(u2), cx = cospi(2.0f * u3), sy = sinpi(2.0f * u3), z = sqrt(fmax(0.0f, 1.0f - u2));
    T ox = tx * r * cx + bx * r * sy + nx * z, oy = ty * r * cx + by * r * sy + ny * z,
      oz = tz * r * cx + bz * r * sy + nz * z;
    const T ol = sqrt(ox * ox + oy * oy + oz * oz);
    ox /= ol;
    oy /= ol;
    oz /= ol;
    const T eps = info->ray_eps + 4e-6f * fmax(fabs(px), fmax(fabs(py), fabs(pz)));

    ST(out, i, LD(out, i) + Lr + ox + px + gx * eps + dist + t);
    ST(out + n, i, LD(out + n, i) + Lg + oy + py + gy * eps);
    ST(out + 2 * n, i, LD(out + 2 * n, i) + Lb + oz + pz + gz * eps);
}

#include "scene/scene_fingerprint.h"

#include <vector>

#include "util/hash.h"

namespace clppm {

uint64_t scene_fingerprint(const Scene& s) {
    uint64_t h = kFnv1a64Basis;
    h = fnv1a64(s.positions, h);
    h = fnv1a64(s.shading, h);
    h = fnv1a64(s.materials, h);
    h = fnv1a64(s.textures, h);
    h = fnv1a64(s.texels, h);
    h = fnv1a64(s.tangents, h); // empty, and so no change, without normal maps
    h = fnv1a64(s.colors, h);   // likewise without COLOR_0
    h = fnv1a64(s.uv1, h);      // and without TEXCOORD_1
    h = fnv1a64(s.punctual_lights, h);
    if (s.environment.present) { // absent, it changes nothing: fingerprints from before stay valid
        const Environment& e = s.environment;
        std::vector<float> v(e.radiance.begin(), e.radiance.end());
        v.insert(v.end(), {float(e.texture), e.rotation, e.hidden ? 1.f : 0.f});
        h = fnv1a64(v, h);
    }
    if (s.medium.present) { // likewise
        const MediumDesc& m = s.medium.medium;
        std::vector<float> v(m.density.begin(), m.density.end());
        v.insert(v.end(), m.albedo.begin(), m.albedo.end());
        v.push_back(m.anisotropy);
        h = fnv1a64(v, h);
    }
    for (const CameraDesc& c : s.cameras) {
        std::vector<float> v(c.position, c.position + 3);
        v.insert(v.end(), c.forward, c.forward + 3);
        v.insert(v.end(), c.up, c.up + 3);
        v.insert(v.end(), {c.yfov, c.aspect, c.aperture_radius, c.focus_distance, c.znear, c.orthographic ? 1.f : 0.f,
                           c.xmag, c.ymag});
        h = fnv1a64(v, h);
    }
    return h;
}

} // namespace clppm

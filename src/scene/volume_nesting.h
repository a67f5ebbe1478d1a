// Which closed volume each surface lies in, so that media nest without a stack on the paths
// (kernels/medium.cl): a segment that ends on a mesh's back face ran inside that mesh; one that
// ends on any other face ran in the volume that encloses the mesh, Material::outside. A fog cube
// with objects and lights in it, wax inside a glass of fog, a medium inside a medium.
#pragma once
#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace clppm {

// For every triangle and every punctual light, a face of the innermost closed volume (a mesh whose
// material has MATERIAL_FLAG_ENCLOSES_VOLUME, of another material than the triangle's own) that
// encloses it, or kNoEnclosure: found by rays from the triangle's centroid (the light's position),
// counting the volumes' faces they cross (the first back face of a volume not entered on the way is
// the container), in three directions with a majority vote (one ray through an edge can
// miscount). Meshes of one material are taken as one (a volume nested in another of its own
// material is not told apart); directional lights lie outside everything.
constexpr uint32_t kNoEnclosure = 0xffffffffu;
struct Enclosures {
    std::vector<uint32_t> triangles, lights;
};
Enclosures enclosures(const Scene& scene);

// Sets Material::outside of every material (0: the world's medium, k + 1: inside material k's
// volume) from enclosures(), appending a copy of a material for each further volume its triangles
// lie in (the copies keep its name) and pointing those triangles at it, and marks the volumes that
// hold a light (an emissive triangle or a punctual light) MATERIAL_FLAG_HOLDS_LIGHTS. Scenes
// without nesting are left as they are. Call once, on the scene as rendered (after the variant).
void nest_volumes(Scene& scene);

} // namespace clppm

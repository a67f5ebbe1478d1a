// glTF skins (glTF 2.0 Sec. 3.7.3): a skinned mesh is drawn where its joints put it, at
// sum_k w_k J_k v with J_k = global(joint_k) x inverseBindMatrix_k, for the joints and weights of
// JOINTS_n / WEIGHTS_n; the transform of the node the mesh hangs on is not applied. clppm renders
// the pose the node transforms give, at the start of the first animation (gltf_animation_pose.h).
#pragma once
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "scene/gltf/gltf_accessors.h"
#include "scene/gltf/gltf_context.h"
#include "scene/gltf/gltf_scene_builder.h"

namespace clppm::gltf {

// J_k for every joint of skin `skin`, from the joints' global transforms (through their
// parents, whether or not the scene draws them) and the inverse bind matrices (identity when
// the skin has none). Fails naming the skin for an out-of-range joint or accessor.
std::vector<glm::dmat4> joint_matrices(const tinygltf::Model& m, const AccessorReader& reader, const LoadContext& ctx,
                                       int skin, const std::string& label);

// Moves the object-space vertices v (positions, normals by the inverse transpose, tangents) by
// the blend of J_k their JOINTS_n / WEIGHTS_n name; weights are renormalised to sum 1 (a vertex
// with no weight keeps its place). Fails naming the primitive for an attribute of the wrong kind
// or a joint index beyond the skin.
void apply_skin(const tinygltf::Primitive& prim, const std::vector<glm::dmat4>& joints, const AccessorReader& reader,
                const LoadContext& ctx, const std::string& label, WorldVertices* v);

} // namespace clppm::gltf

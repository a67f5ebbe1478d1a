#include "scene/gltf/gltf_animation_pose.h"

#include <cmath>
#include <string>
#include <vector>

#include "scene/gltf/gltf_accessors.h"

namespace clppm::gltf {

int apply_animation_start(tinygltf::Model& model, LoadContext& ctx) {
    if (model.animations.empty()) return 0;
    const tinygltf::Animation& anim = model.animations[0];
    AccessorReader reader(model, ctx);
    int applied = 0;
    for (size_t c = 0; c < anim.channels.size(); ++c) {
        const tinygltf::AnimationChannel& ch = anim.channels[c];
        const std::string what = "animation 0 channel " + std::to_string(c);
        const std::string& path = ch.target_path;
        if (path != "translation" && path != "rotation" && path != "scale") continue; // weights, pointers
        if (ch.target_node < 0) continue; // KHR_animation_pointer targets: not read
        if (size_t(ch.target_node) >= model.nodes.size()) ctx.fail(what + " targets a node that does not exist");
        if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size())
            ctx.fail(what + " names a sampler that does not exist");
        const tinygltf::AnimationSampler& s = anim.samplers[size_t(ch.sampler)];
        const int components = path == "rotation" ? 4 : 3;
        AccessorView out = reader.view(s.output, what + " output");
        if (out.components != components)
            ctx.fail(what + ": " + path + " output must be a VEC" + std::to_string(components));
        // CUBICSPLINE stores (in-tangent, value, out-tangent) per keyframe.
        const bool cubic = s.interpolation == "CUBICSPLINE";
        const size_t first = cubic ? 1 : 0;
        const AccessorView in = reader.view(s.input, what + " input");
        if (in.count == 0 || out.count <= first) ctx.fail(what + " has no keyframes");
        const size_t want = in.count * (cubic ? 3 : 1);
        if (out.count != want)
            ctx.fail(what + ": " + std::to_string(out.count) + " output values for " + std::to_string(in.count) +
                     " keyframe times (" + (cubic ? "CUBICSPLINE needs 3 per keyframe: " : "one per keyframe: ") +
                     std::to_string(want) + ")");
        std::vector<double> v(static_cast<size_t>(components));
        for (int k = 0; k < components; ++k) {
            v[size_t(k)] = out.get(first, k);
            if (!std::isfinite(v[size_t(k)])) ctx.fail(what + " has a non-finite keyframe value");
        }
        tinygltf::Node& node = model.nodes[size_t(ch.target_node)];
        if (!node.matrix.empty()) continue; // glTF forbids animating a node with a matrix
        if (path == "translation") node.translation = v;
        else if (path == "rotation") {
            if (!(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3] > 0.0))
                ctx.fail(what + " has a zero rotation quaternion");
            node.rotation = v;
        } else node.scale = v;
        ++applied;
    }
    return applied;
}

} // namespace clppm::gltf

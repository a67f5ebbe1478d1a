#include "render/render_options.h"

#include "io/image_io.h"
#include "render/option_table.h"
#include "render/option_values.h"
#include "util/error.h"

namespace clppm {

bool wants_error_estimate(const RenderOptions& o) { return o.target_error > 0 || !o.error_output.empty(); }

double confidence_of(const RenderOptions& o) { return o.confidence.value_or(kDefaultConfidence); }

uint64_t pass_limit(const RenderOptions& o, uint64_t default_passes) {
    if (o.passes) return *o.passes;
    return o.time_limit > 0 ? 0 : default_passes;
}

std::vector<std::string> output_files(const RenderOptions& o) {
    std::vector<std::string> files;
    if (!o.output.empty()) {
        files.push_back(o.output);
        if (o.write_png) files.push_back(png_path_for(o.output));
    }
    for (const std::string* p : {&o.stats_json, &o.checkpoint})
        if (!p->empty()) files.push_back(*p);
    if (!o.error_output.empty()) {
        files.push_back(o.error_output);
        files.push_back(png_path_for(o.error_output));
    }
    return files;
}

Json options_every_rank_shares(const RenderOptions& o) {
    Json shared = option_values(o, OptionRole::Image);
    shared.update(option_values(o, OptionRole::Run));
    shared["SCENE"] = o.scene;
    return shared;
}

void set_scene(RenderOptions& o, const std::string& path) {
    if (!o.scene.empty()) throw Error("unexpected second scene file " + path + " (already given " + o.scene + ")");
    if (!ends_with_ci(path, ".gltf") && !ends_with_ci(path, ".glb"))
        throw Error("scene file " + path + ": must be a .gltf or .glb file");
    o.scene = path;
}

} // namespace clppm

#include "integrators/integrator.h"

#include <cmath>

#include "integrators/checkpoint_checks.h"
#include "util/error.h"

namespace clppm {

IntegratorBase::IntegratorBase(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                               const cl::Program& program)
    : dc_(dc), scene_(scene), settings_(settings), program_(program),
      num_pixels_(scene.camera.width * scene.camera.height) {}

void IntegratorBase::save(Checkpoint& ck) {
    Json& h = ck.header;
    h["passes"] = stats_.passes;
    h["photons_emitted"] = stats_.photons_emitted;
    h["photons_stored"] = stats_.photons_stored;
    h["hitpoints"] = stats_.hitpoints;
    h["initial_radius"] = stats_.initial_radius;
    h["mean_radius"] = stats_.mean_radius;
    Json phases = Json::object();
    for (const auto& [k, v] : stats_.phase_seconds) phases[k] = v;
    h["phase_seconds"] = phases;
}

void IntegratorBase::restore(const Checkpoint& ck) {
    const Json& h = ck.header;
    for (const char* key : {"passes", "photons_emitted", "photons_stored", "hitpoints"})
        require_checkpoint_field(ck, h.contains(key) && h[key].is_number_unsigned(),
                                 std::string(key) + (h.contains(key) ? " = " + h[key].dump() : " (missing)"));
    try {
        stats_.passes = h.at("passes").get<uint64_t>();
        stats_.photons_emitted = h.at("photons_emitted").get<uint64_t>();
        stats_.photons_stored = h.at("photons_stored").get<uint64_t>();
        stats_.initial_radius = h.at("initial_radius").get<double>();
        stats_.mean_radius = h.at("mean_radius").get<double>();
        if (h.at("hitpoints").get<uint64_t>() != stats_.hitpoints)
            throw Error(ck.path + ": checkpoint has " + h.at("hitpoints").dump() + " hit points, this render " +
                        std::to_string(stats_.hitpoints) + " (a different device or clppm version?)");
        stats_.phase_seconds.clear();
        for (auto it = h.at("phase_seconds").begin(); it != h.at("phase_seconds").end(); ++it) {
            const double s = it.value().get<double>();
            require_checkpoint_field(ck, std::isfinite(s) && s >= 0, "phase_seconds." + it.key());
            stats_.phase_seconds[it.key()] = s;
        }
    } catch (const nlohmann::json::exception& e) {
        throw Error(ck.path + ": checkpoint header lacks the pass counters (" + std::string(e.what()) + ")");
    }
}

void IntegratorBase::enable_error_estimation() {
    throw Error("the " + name() + " integrator does not estimate its error");
}

ErrorImage IntegratorBase::error_estimate(double confidence) {
    if (!errors_) throw Error("the " + name() + " integrator does not estimate its error here");
    return errors_->estimate(confidence, int(scene_.camera.width), int(scene_.camera.height), nullptr,
                             normalization_variance());
}

void IntegratorBase::save_error_stats(Checkpoint& ck) const {
    if (errors_) ck.put("error_stats2", errors_->read());
}

void IntegratorBase::restore_error_stats(const Checkpoint& ck, const cl::Buffer& source) {
    if (!errors_) return;
    auto blob = ck.blobs.find("error_stats2");
    if (blob != ck.blobs.end() && blob->second.size() == size_t(num_pixels_) * sizeof(dev::ErrorStats))
        errors_->write(ck.get<dev::ErrorStats>("error_stats2", num_pixels_));
    else errors_->reset(source); // saved without error estimation: the estimate starts over here
}

} // namespace clppm

// One render's state between passes: the devices, the scene on them, the integrator and its
// kernels, and what the render has estimated of its error (Cycles' Session without its loop).
// The constructor does everything before the first pass; run_pass() adds one; the image, the
// error estimate, the statistics, the outputs and the checkpoint can be taken at any pass
// boundary. render/render_loop.h runs the passes and tells the observers; the command line and the
// Python module are front ends of both.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "device/cl.h"
#include "device/device.h"
#include "device/kernel_program.h"
#include "integrators/error_estimate.h"
#include "integrators/integrator.h"
#include "integrators/integrator_table.h"
#include "io/stats_json.h"
#include "render/render_log.h"
#include "render/render_options.h"
#include "scene/device_scene.h"
#include "scene/scene.h"

namespace clppm {

class OutputLock;

// How a run of passes ended, for the statistics and the outputs.
struct RenderEnd {
    bool interrupted = false;       // Ctrl-C, SIGTERM, KeyboardInterrupt: the last complete pass is kept
    bool stopped_by_viewer = false; // the live view's Stop
    double render_seconds = 0;
    bool nothing_written = false; // interrupted before the first pass: the outputs were left as they were
    size_t defective_pixels = 0;  // NaN, Inf or negative pixels in the image (a renderer defect)
};

class RenderJob {
public:
    // In order: the devices; rank 0's output checks and locks (before hours of rendering, not
    // after); the scene and its world; the integrator ("auto": the default for the scene); the
    // memory check; the scene on the device; the kernels; a resumed checkpoint; prepare(). Throws
    // Error with the one-line message for any bad input.
    RenderJob(const RenderOptions& options, RenderLog& log);
    ~RenderJob();
    RenderJob(const RenderJob&) = delete;
    RenderJob& operator=(const RenderJob&) = delete;

    // One pass; throws PassCancelled when a stop was requested in it (the state is then the last
    // complete pass's). Updates the error estimate when estimating.
    // With max_passes > 1 the integrator may run up to that many passes at once (the path tracer
    // batches short passes into one launch; its image is the same).
    void run_pass(uint64_t max_passes = 1);

    // The options as rendered: the integrator resolved, the size as the camera gave it.
    const RenderOptions& options() const { return options_; }
    const IntegratorRow& integrator() const { return *row_; }
    const IntegratorStats& stats() const { return integ_->stats(); }
    uint64_t passes() const { return integ_->stats().passes; }
    // Passes the checkpoint held when resumed (0 for a fresh render).
    uint64_t resumed_at() const { return resumed_at_; }
    // The pass limit (0: none): --passes, else the integrator's default without --time.
    uint64_t pass_limit() const;
    // Seconds since rendering started (the first eye pass included).
    double render_seconds() const;
    int width() const;
    int height() const;
    // Rank 0 of several processes, or the only one: it speaks, serves and writes.
    bool writer() const { return writer_; }
    RenderLog& log() const { return log_; }

    // The image after the last pass, with EXR attributes that say how it came to be (version,
    // integrator, passes, interrupted, the PNG's tone curve and exposure).
    Image image(bool interrupted = false) const;

    // Error estimation (--target-error, --error-output): the estimate after the last pass.
    bool estimating() const { return estimating_; }
    const ErrorImage& error() const { return error_; }
    // The measure the target applies to: the calibrated estimate, or with --error-bound the bound.
    double error_measure() const;
    // Whether the target is reached (never before kMinPassesToStop passes).
    bool error_target_reached() const;
    // Seconds to the target at the recent pace; < 0 when unknown.
    double error_eta() const;

    // The image at `exr_path` (with the error layer when estimating) and, with `png`, its PNG.
    void save_images(const std::string& exr_path, bool png, bool interrupted = false) const;
    void save_images(const std::string& exr_path, bool png, const Image& img) const;
    // The outputs the options name: the image (`img`, this job's image()) and PNG, and the error image.
    void save_outputs(bool interrupted = false) const;
    void save_outputs(const Image& img) const;
    // The progressive state to the options' checkpoint file.
    void save_checkpoint() const;
    // --stats-json's content; `img`: the image() it describes, if already at hand.
    Json stats_json(const RenderEnd& end, const Image* img = nullptr) const;

private:
    void load_scene();
    void choose_integrator(size_t devices);
    void set_up_device(const std::vector<DeviceInfo>& chosen);
    void build_kernels(const std::vector<DeviceInfo>& chosen);
    void resume();

    RenderOptions options_;
    RenderLog& log_;
    bool writer_;
    double created_s_; // on the steady clock
    std::unique_ptr<OutputLock> lock_;
    const IntegratorRow* row_ = nullptr;
    Scene scene_;
    uint64_t scene_hash_ = 0;
    std::string integrator_note_;
    std::string photons_note_; // the photons per pass the scene chose ("" where --photons or the default holds)
    std::string world_note_;   // which world the render uses, and where it came from
    std::string medium_note_;  // its medium, and where that came from ("" for none)
    std::string variant_note_; // the file's material variants and the one rendered
    std::unique_ptr<DeviceContext> dc_;
    std::unique_ptr<DeviceScene> ds_;
    std::string features_;
    ProgramBuildStats build_;
    Json fingerprint_;
    cl::Program program_;
    std::unique_ptr<IntegratorBase> integ_;
    double start_s_ = 0; // when rendering started, on the steady clock
    uint64_t resumed_at_ = 0;
    bool estimating_ = false;
    ErrorImage error_;
    ErrorTrend trend_;
};

} // namespace clppm

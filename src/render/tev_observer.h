// --display-server as an observer of the loop: the image goes to tev (render/tev_client.h) at most
// LiveView::kPublishHz times a second and once at the end; what the client has to say of the
// viewer (gone, not reading) is said once, as a warning.
#pragma once
#include <memory>
#include <string>

#include "render/render_observer.h"
#include "render/tev_client.h"

namespace clppm {

class TevObserver : public RenderObserver {
public:
    static constexpr double kFinalFlushSeconds = 2.0; // the final image's wait at most

    // Connects; throws Error naming --display-server when it cannot. The image is named after
    // the output's file name (or "clppm" without one).
    TevObserver(const std::string& address, const std::string& output);
    void pass_done(RenderJob& job) override;
    void finished(RenderJob& job, const RenderEnd& end) override;

private:
    void say(RenderJob& job);

    std::unique_ptr<TevClient> tev_;
    double last_send_s_ = -1e9;
};

} // namespace clppm

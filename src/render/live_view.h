// --serve [ADDR:]PORT: a live view of the render in a browser. An HTTP server (cpp-httplib) on
// its own threads serves a page (cli/live_view_page.h: no external resources) and what the render
// loop last published: the image as a PNG through the PNG's tone curve at an exposure the page
// chooses, or as half floats (io/half_image.h) for the page to tone-map itself, the per-pixel
// error map, and the progress as JSON; POST /save asks the loop to write
// the outputs after the current pass, POST /stop to end the render after it, as Ctrl-C does.
//
// The render loop publishes only while someone watches (a request in the last few seconds) and
// at most kPublishHz times a second, so an unwatched render pays nothing and a watched one a
// film readback now and then; the server never blocks the loop (one mutex, held for a copy).
// Watching changes no image: publishing reads the film, it does not touch the statistics.
#pragma once
#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/image_io.h"
#include "io/tone_map.h"

namespace httplib {
class Server;
}

namespace clppm {

// "8080" -> {"127.0.0.1", 8080}; "0.0.0.0:8080"; "[::1]:8080". Port 0 picks a free one. Throws
// clppm::Error naming --serve for anything else.
struct ServeAddress {
    std::string host;
    int port = 0;
};
ServeAddress parse_serve_address(const std::string& text);
// Whether the address only this machine can reach (127.0.0.0/8, ::1, localhost).
bool is_loopback(const std::string& host);

class LiveView {
public:
    static constexpr double kPublishHz = 4.0;
    static constexpr double kWatchedSeconds = 5.0; // a viewer counts as watching this long after a request

    // Binds and starts serving; throws clppm::Error naming --serve when the address cannot be bound.
    // `tone`: the PNG's curve and exposure, to which the page's exposure adds.
    LiveView(const ServeAddress& address, const ToneMapping& tone);
    ~LiveView();
    LiveView(const LiveView&) = delete;
    LiveView& operator=(const LiveView&) = delete;

    int port() const { return port_; }
    std::string url() const;

    // Whether publish() is worth calling now: someone watched recently and the last publication
    // is at least 1 / kPublishHz old.
    bool due() const;
    // The current image, its per-pixel relative error (empty when not estimating; `error_scale` is
    // the top of its colour ramp) and the progress JSON. Copies; returns at once.
    void publish(const Image& image, const std::vector<float>& error_relative, double error_scale,
                 const nlohmann::json& progress);
    // The JSON /stats answers with from now on even without an image (e.g. "finished").
    void set_state(const std::string& state);

    bool stop_requested() const { return stop_.load(); }
    // True once for each POST /save since the last call.
    bool take_save_request() { return save_.exchange(false); }
    // Requests served so far (for tests and stats).
    uint64_t requests() const { return requests_.load(); }

private:
    struct Snapshot {
        Image image;
        std::vector<float> error;
        double error_scale = 0.2;
        double base_ev = 0; // the exposure the PNG applies to `image` (ToneMapping's, auto included)
        nlohmann::json progress = nlohmann::json::object();
        uint64_t version = 0; // increments with every publication
        std::string state = "starting";
    };
    void routes();
    void touched(); // a request arrived: someone is watching

    std::unique_ptr<httplib::Server> server_;
    std::thread thread_;
    int port_ = 0;
    std::string host_;
    ToneMapping tone_;
    mutable std::mutex mutex_;
    Snapshot snapshot_;
    std::atomic<bool> stop_{false}, save_{false};
    std::atomic<uint64_t> requests_{0};
    std::atomic<double> last_request_s_{-1e9}; // steady clock seconds (now_seconds in live_view.cpp)
    double last_publish_s_ = -1e9;             // the render thread's own
};

} // namespace clppm

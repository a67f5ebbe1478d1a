#include "render/live_view.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>

#include <httplib.h>

#include "integrators/error_estimate.h" // false_colour
#include "io/half_image.h"
#include "render/live_view_page.h"
#include "util/error.h"
#include "util/steady_seconds.h"

namespace clppm {

namespace {

[[noreturn]] void bad_address(const std::string& text, const std::string& why) {
    throw Error("--serve " + (text.empty() ? std::string("''") : text) + ": " + why);
}

void json_reply(httplib::Response& res, int status, const nlohmann::json& j) {
    res.status = status;
    res.set_header("Cache-Control", "no-store");
    res.set_content(j.dump(), "application/json");
}

void image_headers(httplib::Response& res, uint64_t version, double encode_s) {
    res.set_header("Cache-Control", "no-store");
    res.set_header("X-Clppm-Version", std::to_string(version));
    char timing[64];
    std::snprintf(timing, sizeof timing, "encode;dur=%.3f", encode_s * 1e3);
    res.set_header("Server-Timing", timing);
}

} // namespace

ServeAddress parse_serve_address(const std::string& text) {
    ServeAddress a;
    a.host = "127.0.0.1";
    std::string port = text;
    const size_t colon = text.rfind(':');
    if (colon != std::string::npos) {
        a.host = text.substr(0, colon);
        port = text.substr(colon + 1);
        if (a.host.size() >= 2 && a.host.front() == '[' && a.host.back() == ']')
            a.host = a.host.substr(1, a.host.size() - 2);
        if (a.host.empty()) bad_address(text, "must be [ADDR:]PORT with an address before the ':'");
    }
    char* end = nullptr;
    const long p = port.empty() ? -1 : std::strtol(port.c_str(), &end, 10);
    if (port.empty() || *end != '\0' || p < 0 || p > 65535)
        bad_address(text, "must be [ADDR:]PORT with a port in 0..65535 (0: any free port)");
    a.port = int(p);
    return a;
}

bool is_loopback(const std::string& host) { return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0; }

LiveView::LiveView(const ServeAddress& address, const ToneMapping& tone)
    : server_(std::make_unique<httplib::Server>()), host_(address.host), tone_(tone) {
    routes();
    // httplib's default also sets SO_REUSEPORT, which would let a second render bind the same port
    // and take half the page's requests: SO_REUSEADDR alone (a restart may reuse a port in TIME_WAIT).
    server_->set_socket_options([](socket_t sock) {
        int yes = 1;
        ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    });
    port_ = address.port == 0 ? server_->bind_to_any_port(address.host)
                              : (server_->bind_to_port(address.host, address.port) ? address.port : -1);
    if (port_ <= 0)
        throw Error("--serve " + address.host + ":" + std::to_string(address.port) +
                    ": cannot listen there (address not on this machine, or port in use)");
    thread_ = std::thread([this] { server_->listen_after_bind(); });
    // httplib's stop() does nothing until the server runs, and a listen that starts after it would
    // never end: the destructor's join would hang. Return only once it runs.
    const double deadline = steady_seconds() + 30;
    while (!server_->is_running() && steady_seconds() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    if (!server_->is_running()) {
        server_->stop();
        thread_.join(); // listen_after_bind has returned: it never ran
        throw Error("--serve " + url() + ": the server did not start");
    }
}

LiveView::~LiveView() {
    server_->stop();
    if (thread_.joinable()) thread_.join();
}

std::string LiveView::url() const {
    const bool v6 = host_.find(':') != std::string::npos;
    return "http://" + (v6 ? "[" + host_ + "]" : host_) + ":" + std::to_string(port_) + "/";
}

void LiveView::touched() {
    ++requests_;
    last_request_s_ = steady_seconds();
}

bool LiveView::due() const {
    const double now = steady_seconds();
    return now - last_request_s_.load() <= kWatchedSeconds && now - last_publish_s_ >= 1.0 / kPublishHz;
}

void LiveView::publish(const Image& image, const std::vector<float>& error_relative, double error_scale,
                       const nlohmann::json& progress) {
    last_publish_s_ = steady_seconds();
    std::lock_guard<std::mutex> lock(mutex_);
    snapshot_.image = image;
    snapshot_.image.attributes.clear();
    snapshot_.error = error_relative;
    snapshot_.error_scale = error_scale;
    snapshot_.base_ev = applied_exposure_ev(tone_, image);
    snapshot_.progress = progress;
    snapshot_.state = "rendering";
    ++snapshot_.version;
}

void LiveView::set_state(const std::string& state) {
    std::lock_guard<std::mutex> lock(mutex_);
    snapshot_.state = state;
}

void LiveView::routes() {
    httplib::Server& s = *server_;
    s.Get("/", [this](const httplib::Request&, httplib::Response& res) {
        touched();
        res.set_header("Cache-Control", "no-store");
        res.set_content(live_view_page(), "text/html; charset=utf-8");
    });
    s.Get("/stats", [this](const httplib::Request&, httplib::Response& res) {
        touched();
        std::lock_guard<std::mutex> lock(mutex_);
        json_reply(res, 200,
                   {{"state", snapshot_.state},
                    {"version", snapshot_.version},
                    {"has_error_map", !snapshot_.error.empty()},
                    {"width", snapshot_.image.width},
                    {"height", snapshot_.image.height},
                    {"tone", {{"curve", to_string(tone_.curve)}, {"base_ev", snapshot_.base_ev}}},
                    {"progress", snapshot_.progress}});
    });
    // Both images are encoded here, on the server's thread, from a copy: the render loop only
    // copied. Each says which publication it is (X-Clppm-Version) and what encoding it cost
    // (Server-Timing), which the page shows and bench/live_view_transport.sh measures.
    s.Get("/image.png", [this](const httplib::Request& req, httplib::Response& res) {
        touched();
        ToneMapping tone = tone_;
        if (req.has_param("ev")) {
            char* end = nullptr;
            const std::string v = req.get_param_value("ev");
            const double ev = std::strtod(v.c_str(), &end);
            if (v.empty() || *end != '\0' || !(ev >= -64 && ev <= 64))
                return json_reply(res, 400, {{"error", "ev must be a number in -64..64"}});
            tone.exposure_ev += ev;
        }
        const bool error_map = req.has_param("map") && req.get_param_value("map") == "error";
        if (req.has_param("map") && !error_map) return json_reply(res, 400, {{"error", "map must be error"}});
        Image img;
        uint64_t version = 0;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (snapshot_.version == 0) return json_reply(res, 503, {{"error", "no image yet: the first pass runs"}});
            if (error_map && snapshot_.error.empty())
                return json_reply(res, 404, {{"error", "no error map: the render does not estimate its error"}});
            img = error_map ? false_colour(snapshot_.error, snapshot_.image.width, snapshot_.image.height,
                                           snapshot_.error_scale)
                            : snapshot_.image;
            version = snapshot_.version;
        }
        const double t0 = steady_seconds();
        std::string png = encode_png(img, error_map ? ToneMapping{ToneCurve::Clip, 0.0, false} : tone);
        image_headers(res, version, steady_seconds() - t0);
        res.set_content(std::move(png), "image/png");
    });
    s.Get("/image.f16", [this](const httplib::Request&, httplib::Response& res) {
        touched();
        Image img;
        uint64_t version = 0;
        double base_ev = 0;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (snapshot_.version == 0) return json_reply(res, 503, {{"error", "no image yet: the first pass runs"}});
            img = snapshot_.image;
            version = snapshot_.version;
            base_ev = snapshot_.base_ev;
        }
        const double t0 = steady_seconds();
        std::string bytes = encode_half_image(img, base_ev);
        image_headers(res, version, steady_seconds() - t0);
        res.set_content(std::move(bytes), "application/octet-stream");
    });
    s.Post("/save", [this](const httplib::Request&, httplib::Response& res) {
        touched();
        save_ = true;
        json_reply(res, 202, {{"saving", "after the current pass"}});
    });
    s.Post("/stop", [this](const httplib::Request&, httplib::Response& res) {
        touched();
        stop_ = true;
        json_reply(res, 202, {{"stopping", "after the current pass"}});
    });
    // A known path with the wrong method: 405; anything else: 404; both as JSON.
    const auto not_allowed = [](const httplib::Request&, httplib::Response& res) {
        json_reply(res, 405, {{"error", "method not allowed"}});
    };
    for (const char* path : {"/", "/stats", "/image.png", "/image.f16"}) s.Post(path, not_allowed);
    for (const char* path : {"/save", "/stop"}) s.Get(path, not_allowed);
    s.set_error_handler([](const httplib::Request&, httplib::Response& res) {
        if (!res.body.empty()) return; // a handler's own message
        json_reply(res, res.status, {{"error", res.status == 404 ? "not found" : "bad request"}});
    });
}

} // namespace clppm

// --serve: the live view's server on its own (addresses, endpoints, status codes, what publishing
// changes), and in a render (the endpoints answer while it runs, the image changes between
// passes, save and stop do what they say, a bad request leaves the render going, and being
// watched changes no pixel).
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <chrono>
#include <fstream>
#include <netinet/in.h>
#include <sys/socket.h>
#include <thread>
#include <unistd.h>

#include <httplib.h>
#include <nlohmann/json.hpp>
#include <stb_image.h>

#include "io/half_image.h"
#include "io/image_io.h"
#include "render/live_view.h"
#include "test_util.h"
#include "util/error.h"

using namespace clppm;
using namespace clppm::test;

namespace {

Image flat(int w, int h, float v) {
    Image img;
    img.width = w, img.height = h;
    img.rgb.assign(size_t(w) * size_t(h) * 3, v);
    return img;
}

bool is_png(const std::string& body) { return body.size() > 8 && body.compare(1, 3, "PNG") == 0; }

// Polls `path` on 127.0.0.1:port until it answers (the render starts its server after loading).
httplib::Result get_when_up(httplib::Client& c, const std::string& path, double seconds = 60) {
    const auto t0 = std::chrono::steady_clock::now();
    for (;;) {
        httplib::Result r = c.Get(path.c_str());
        if (r || std::chrono::steady_clock::now() - t0 > std::chrono::duration<double>(seconds)) return r;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
}

// A port nobody uses now: bind one, read it, let it go.
int free_port() {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof a;
    const bool ok = ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
                    ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) == 0;
    ::close(fd);
    return ok ? ntohs(a.sin_port) : -1;
}

} // namespace

TEST(LiveView, AddressesAreParsedOrRefused) {
    ServeAddress a = parse_serve_address("8080");
    EXPECT_EQ(a.host, "127.0.0.1");
    EXPECT_EQ(a.port, 8080);
    a = parse_serve_address("0.0.0.0:0");
    EXPECT_EQ(a.host, "0.0.0.0");
    EXPECT_EQ(a.port, 0);
    a = parse_serve_address("[::1]:9000");
    EXPECT_EQ(a.host, "::1");
    EXPECT_EQ(a.port, 9000);
    for (const char* bad : {"", "x", "65536", "-1", ":80", "host:", "1.2.3.4:http"}) {
        try {
            parse_serve_address(bad);
            ADD_FAILURE() << bad << " was accepted";
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()).rfind("--serve ", 0), 0u) << e.what();
        }
    }
    EXPECT_TRUE(is_loopback("127.0.0.1"));
    EXPECT_TRUE(is_loopback("localhost"));
    EXPECT_TRUE(is_loopback("::1"));
    EXPECT_FALSE(is_loopback("0.0.0.0"));
    EXPECT_FALSE(is_loopback("192.168.1.2"));
}

// The server alone: the page, /stats, the image as PNG (503 before the first publication, new
// bytes after the next), the error map only when there is one, 400 for a bad exposure, 404 for
// an unknown path, 405 for a wrong method; /save and /stop only raise flags.
TEST(LiveView, EndpointsAnswerAndPublishingShows) {
    LiveView view(parse_serve_address("127.0.0.1:0"), ToneMapping{});
    ASSERT_GT(view.port(), 0);
    EXPECT_EQ(view.url(), "http://127.0.0.1:" + std::to_string(view.port()) + "/");
    httplib::Client c("127.0.0.1", view.port());
    auto page = c.Get("/");
    ASSERT_TRUE(page);
    EXPECT_EQ(page->status, 200);
    EXPECT_NE(page->body.find("<canvas id=\"img\""), std::string::npos);
    EXPECT_EQ(page->body.find("http://"), std::string::npos); // no external resources
    EXPECT_EQ(page->body.find("https://"), std::string::npos);

    auto stats = c.Get("/stats");
    ASSERT_TRUE(stats);
    nlohmann::json j = nlohmann::json::parse(stats->body);
    EXPECT_EQ(j["version"], 0);
    EXPECT_EQ(j["state"], "starting");
    EXPECT_EQ(c.Get("/image.png")->status, 503);
    EXPECT_EQ(c.Get("/image.f16")->status, 503);
    EXPECT_TRUE(view.due()); // someone asked, nothing published yet

    view.publish(flat(4, 2, 0.25f), {}, 0.2, {{"pass", 1}});
    EXPECT_FALSE(view.due()); // not again before 1 / kPublishHz
    auto img1 = c.Get("/image.png");
    ASSERT_TRUE(img1);
    EXPECT_EQ(img1->status, 200);
    EXPECT_TRUE(is_png(img1->body));
    EXPECT_EQ(img1->get_header_value("Content-Type"), "image/png");
    auto brighter = c.Get("/image.png?ev=2");
    ASSERT_TRUE(brighter);
    EXPECT_NE(brighter->body, img1->body);
    EXPECT_EQ(c.Get("/image.png?ev=abc")->status, 400);
    EXPECT_EQ(c.Get("/image.png?ev=100")->status, 400);
    EXPECT_EQ(c.Get("/image.png?map=error")->status, 404); // no error estimate
    EXPECT_EQ(c.Get("/image.png?map=foo")->status, 400);
    // The half floats: the values, at the PNG's exposure (0 here), with the publication's number.
    auto halves = c.Get("/image.f16");
    ASSERT_TRUE(halves);
    EXPECT_EQ(halves->status, 200);
    EXPECT_EQ(halves->get_header_value("Content-Type"), "application/octet-stream");
    EXPECT_EQ(halves->get_header_value("X-Clppm-Version"), "1");
    EXPECT_EQ(img1->get_header_value("X-Clppm-Version"), "1");
    EXPECT_EQ(halves->get_header_value("Server-Timing").rfind("encode;dur=", 0), 0u);
    const HalfImage h = decode_half_image(halves->body);
    EXPECT_EQ(h.width, 4u);
    EXPECT_EQ(h.height, 2u);
    EXPECT_EQ(h.base_ev, 0.0f);
    EXPECT_EQ(h.rgb, std::vector<float>(24, 0.25f));

    view.publish(flat(4, 2, 0.5f), std::vector<float>(8, 0.1f), 0.2, {{"pass", 2}});
    auto img2 = c.Get("/image.png");
    ASSERT_TRUE(img2);
    EXPECT_NE(img2->body, img1->body);
    auto map = c.Get("/image.png?map=error");
    ASSERT_TRUE(map);
    EXPECT_EQ(map->status, 200);
    EXPECT_TRUE(is_png(map->body));
    j = nlohmann::json::parse(c.Get("/stats")->body);
    EXPECT_EQ(j["version"], 2);
    EXPECT_EQ(j["state"], "rendering");
    EXPECT_EQ(j["has_error_map"], true);
    EXPECT_EQ(j["progress"]["pass"], 2);
    EXPECT_EQ(j["width"], 4);
    EXPECT_EQ(j["tone"]["curve"], "clip");
    EXPECT_EQ(j["tone"]["base_ev"], 0.0);

    EXPECT_EQ(c.Get("/nope")->status, 404);
    EXPECT_EQ(c.Post("/image.png", "", "text/plain")->status, 405);
    EXPECT_EQ(c.Post("/image.f16", "", "text/plain")->status, 405);
    EXPECT_EQ(c.Get("/stop")->status, 405);
    EXPECT_FALSE(view.stop_requested());
    EXPECT_FALSE(view.take_save_request());
    EXPECT_EQ(c.Post("/save", "", "text/plain")->status, 202);
    EXPECT_TRUE(view.take_save_request());
    EXPECT_FALSE(view.take_save_request()); // once per request
    EXPECT_EQ(c.Post("/stop", "", "text/plain")->status, 202);
    EXPECT_TRUE(view.stop_requested());
    view.set_state("finished");
    EXPECT_EQ(nlohmann::json::parse(c.Get("/stats")->body)["state"], "finished");
    EXPECT_GE(view.requests(), 15u);
}

// The half floats carry what the PNG shows: tone-mapped here at no further exposure, they give
// the server's PNG within one 8-bit level (binary16 rounding moves a value across a level's edge
// now and then), over an HDR ramp of seven decades with the automatic exposure and ACES curve.
TEST(LiveView, HalfFloatsCarryWhatThePngShows) {
    const ToneMapping tone{ToneCurve::Aces, 1.5, true};
    LiveView view(parse_serve_address("127.0.0.1:0"), tone);
    Image ramp;
    ramp.width = 256, ramp.height = 4;
    for (int y = 0; y < ramp.height; ++y)
        for (int x = 0; x < ramp.width; ++x)
            for (int c = 0; c < 3; ++c) ramp.rgb.push_back(float(1e-4 * std::pow(10.0, 7.0 * x / 255.0) * (1 + c + y)));
    view.publish(ramp, {}, 0.2, {{"pass", 1}});
    httplib::Client c("127.0.0.1", view.port());
    auto halves = c.Get("/image.f16"), png = c.Get("/image.png");
    ASSERT_TRUE(halves && png);
    const HalfImage h = decode_half_image(halves->body);
    EXPECT_FLOAT_EQ(h.base_ev, float(applied_exposure_ev(tone, ramp)));
    Image mine;
    mine.width = int(h.width), mine.height = int(h.height), mine.rgb = h.rgb;
    const std::string mine_png = encode_png(mine, ToneMapping{ToneCurve::Aces, 0.0, false});
    int w = 0, hh = 0, n = 0, w2 = 0, h2 = 0;
    unsigned char* a = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(png->body.data()),
                                             int(png->body.size()), &w, &hh, &n, 3);
    unsigned char* b = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(mine_png.data()),
                                             int(mine_png.size()), &w2, &h2, &n, 3);
    ASSERT_TRUE(a && b);
    ASSERT_EQ(w * hh, w2 * h2);
    size_t differ = 0;
    int max_diff = 0;
    for (int i = 0; i < 3 * w * hh; ++i) {
        const int d = std::abs(int(a[i]) - int(b[i]));
        differ += d != 0;
        max_diff = std::max(max_diff, d);
    }
    stbi_image_free(a);
    stbi_image_free(b);
    std::printf("%zu of %d values differ, by at most %d\n", differ, 3 * w * hh, max_diff);
    EXPECT_LE(max_diff, 1);
    EXPECT_LE(differ, size_t(3 * w * hh) / 50);
}

TEST(LiveView, AnAddressInUseIsAOneLineError) {
    LiveView first(parse_serve_address("127.0.0.1:0"), ToneMapping{});
    try {
        LiveView second(parse_serve_address("127.0.0.1:" + std::to_string(first.port())), ToneMapping{});
        ADD_FAILURE() << "bound the same port twice";
    } catch (const Error& e) {
        EXPECT_NE(
            std::string(e.what()).find("--serve 127.0.0.1:" + std::to_string(first.port()) + ": cannot listen there"),
            std::string::npos)
            << e.what();
    }
}

// A render with --serve: while it runs the page, stats and image answer, the image changes from
// pass to pass, a bad request gets a 4xx and the render goes on, /save writes the outputs, /stop
// ends it cleanly (exit 0, the image written, the stats say who stopped it).
TEST(LiveView, ARenderCanBeWatchedSavedAndStopped) {
    const std::string dir = make_temp_dir("live");
    const int port = free_port();
    ASSERT_GT(port, 0);
    std::string out;
    int status = -1;
    std::thread render([&] {
        status =
            run_clppm("--integrator sppm --width 32 --height 32 --photons 20000 --passes 100000 --no-png -o " + dir +
                          "/live.exr --stats-json " + dir + "/stats.json --serve 127.0.0.1:" + std::to_string(port),
                      &out);
    });
    httplib::Client c("127.0.0.1", port);
    auto page = get_when_up(c, "/");
    ASSERT_TRUE(page) << "the server never answered";
    EXPECT_EQ(page->status, 200);
    // Two images from different passes differ.
    std::string first_png;
    int first_pass = 0;
    const auto t0 = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60)) {
        const nlohmann::json j = nlohmann::json::parse(c.Get("/stats")->body);
        const int pass = j["progress"].value("pass", 0);
        if (j["version"].get<int>() > 0) {
            auto img = c.Get("/image.png");
            ASSERT_TRUE(img);
            if (first_png.empty() && img->status == 200) first_png = img->body, first_pass = pass;
            else if (!first_png.empty() && pass > first_pass + 1 && img->body != first_png) break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    ASSERT_FALSE(first_png.empty());
    auto later = c.Get("/image.png");
    ASSERT_TRUE(later);
    EXPECT_NE(later->body, first_png) << "the image did not change between passes";
    EXPECT_EQ(c.Get("/image.png?ev=zzz")->status, 400); // and the render goes on:
    EXPECT_EQ(c.Get("/stats")->status, 200);
    // Save: the outputs appear while the render still runs.
    EXPECT_EQ(c.Post("/save", "", "text/plain")->status, 202);
    for (int i = 0; i < 200 && !std::ifstream(dir + "/live.exr").good(); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    EXPECT_TRUE(std::ifstream(dir + "/live.exr").good()) << "/save wrote nothing";
    EXPECT_EQ(c.Post("/stop", "", "text/plain")->status, 202);
    render.join();
    EXPECT_EQ(status, 0) << out;
    EXPECT_NE(out.find("live view at http://127.0.0.1:" + std::to_string(port) + "/"), std::string::npos) << out;
    EXPECT_NE(out.find("from the live view"), std::string::npos) << out;
    std::ifstream js(dir + "/stats.json");
    const nlohmann::json st = nlohmann::json::parse(js);
    EXPECT_EQ(st["live_view"]["stopped_it"], true);
    EXPECT_LT(st["passes"].get<int>(), 100000);
    EXPECT_EQ(read_exr(dir + "/live.exr").width, 32);
}

// Watching changes nothing: the same render with a viewer pulling images all along and without
// --serve gives the same pixels, bit for bit.
TEST(LiveView, BeingWatchedChangesNoPixel) {
    const std::string dir = make_temp_dir("live_same");
    const std::string common = "--integrator sppm --width 32 --height 32 --photons 20000 --passes 40 --quiet --no-png";
    std::string out;
    ASSERT_EQ(run_clppm(common + " -o " + dir + "/plain.exr", &out), 0) << out;
    const int port = free_port();
    int status = -1;
    std::atomic<bool> done{false};
    std::thread render([&] {
        status = run_clppm(common + " -o " + dir + "/watched.exr --serve 127.0.0.1:" + std::to_string(port), &out);
        done = true;
    });
    httplib::Client c("127.0.0.1", port);
    int images = 0;
    while (!done) {
        auto r = c.Get("/image.png");
        if (r && r->status == 200) ++images;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    render.join();
    ASSERT_EQ(status, 0) << out;
    std::printf("%d images pulled during the watched render\n", images);
    EXPECT_GT(images, 0);
    const Image a = read_exr(dir + "/plain.exr"), b = read_exr(dir + "/watched.exr");
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    EXPECT_TRUE(a.rgb == b.rgb) << "the watched render differs";
}

// A real browser: headless Chromium loads the page during a render and its screenshot shows the
// image (the Cornell box's red and green walls). Skipped, saying so, where chromium is absent
// (scripts/install-deps.sh installs it when Debian has it).
TEST(LiveView, ABrowserShowsTheImage) {
    std::string out;
    if (run_command("command -v chromium", &out) != 0) GTEST_SKIP() << "chromium is not installed";
    const std::string dir = make_temp_dir("live_browser");
    const int port = free_port();
    int status = -1;
    std::thread render([&] {
        status = run_clppm("--width 96 --height 96 --passes 100000 --quiet --no-png -o " + dir +
                               "/b.exr --serve 127.0.0.1:" + std::to_string(port),
                           &out);
    });
    httplib::Client c("127.0.0.1", port);
    ASSERT_TRUE(get_when_up(c, "/stats"));
    // Watched from here on: wait for the first published image.
    for (int i = 0; i < 600; ++i) {
        auto r = c.Get("/stats");
        if (r && nlohmann::json::parse(r->body)["version"].get<int>() > 0) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    std::string log;
    const int rc = run_command(
        "timeout 120 chromium --headless --no-sandbox --disable-gpu --screenshot=" + dir +
            "/shot.png --window-size=400,300 --virtual-time-budget=3000 http://127.0.0.1:" + std::to_string(port) + "/",
        &log);
    c.Post("/stop", "", "text/plain");
    render.join();
    EXPECT_EQ(status, 0) << out;
    ASSERT_EQ(rc, 0) << log;
    int w = 0, h = 0, n = 0;
    unsigned char* px = stbi_load((dir + "/shot.png").c_str(), &w, &h, &n, 3);
    ASSERT_NE(px, nullptr) << "no screenshot";
    size_t red = 0, green = 0;
    for (int i = 0; i < w * h; ++i) {
        const unsigned char r = px[3 * i], g = px[3 * i + 1], b = px[3 * i + 2];
        red += r > 120 && g < 70 && b < 70;
        green += g > 100 && r < 70 && b < 70;
    }
    stbi_image_free(px);
    std::printf("screenshot %dx%d: %zu red and %zu green pixels\n", w, h, red, green);
    EXPECT_GT(red, 50u) << "the page shows no image";
    EXPECT_GT(green, 50u) << "the page shows no image";
}

namespace {

// Runs headless Chromium on `url` until the page's title holds JSON (the page's ?check and ?bench
// modes put their result there), read from the DevTools HTTP endpoint, which needs no protocol
// client; real time throughout (a headless browser's virtual time skips network waits and would
// dump the page between two fetches). Empty when chromium is missing or the page never answered.
nlohmann::json page_result(const std::string& url, const std::string& dir, double seconds) {
    const int devtools = free_port();
    std::string log;
    run_command("(timeout " + std::to_string(int(seconds) + 30) +
                    " chromium --headless --no-sandbox --disable-gpu --user-data-dir=" + dir +
                    "/profile --remote-debugging-port=" + std::to_string(devtools) + " '" + url +
                    "' >/dev/null 2>&1 & echo $! > " + dir + "/chromium.pid)",
                &log);
    httplib::Client d("127.0.0.1", devtools);
    nlohmann::json result;
    const auto t0 = std::chrono::steady_clock::now();
    while (result.is_null() && std::chrono::steady_clock::now() - t0 < std::chrono::duration<double>(seconds)) {
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        auto r = d.Get("/json/list");
        if (!r || r->status != 200) continue;
        for (const auto& target : nlohmann::json::parse(r->body, nullptr, false)) {
            if (!target.is_object() || target.value("type", "") != "page") continue;
            std::string title = target.value("title", "");
            for (size_t at; (at = title.find("&quot;")) != std::string::npos;) title.replace(at, 6, "\"");
            if (!title.empty() && title.front() == '{') result = nlohmann::json::parse(title, nullptr, false);
        }
    }
    run_command("kill $(cat " + dir + "/chromium.pid) 2>/dev/null; pkill -f 'remote-debugging-port=" +
                    std::to_string(devtools) + "' 2>/dev/null; true",
                &log);
    return result;
}

} // namespace

// The page's own tone mapping: in a real browser, the half floats drawn by the page's script
// against the server's PNG of the same publication, value for value (one 8-bit level apart now and
// then, from binary16 rounding, as HalfFloatsCarryWhatThePngShows measures in C++).
TEST(LiveView, ThePageToneMapsAsTheServerDoes) {
    std::string out;
    if (run_command("command -v chromium", &out) != 0) GTEST_SKIP() << "chromium is not installed";
    const std::string dir = make_temp_dir("live_check");
    const int port = free_port();
    int status = -1;
    std::thread render([&] {
        status = run_clppm("--width 96 --height 96 --tonemap aces --passes 100000 --quiet --no-png -o " + dir +
                               "/c.exr --serve 127.0.0.1:" + std::to_string(port),
                           &out);
    });
    httplib::Client c("127.0.0.1", port);
    ASSERT_TRUE(get_when_up(c, "/stats"));
    const nlohmann::json r = page_result("http://127.0.0.1:" + std::to_string(port) + "/?check=1", dir, 90);
    c.Post("/stop", "", "text/plain");
    render.join();
    EXPECT_EQ(status, 0) << out;
    ASSERT_TRUE(r.is_object()) << "the page reported nothing";
    ASSERT_FALSE(r.contains("error")) << r.dump();
    std::printf("page check: %s\n", r.dump().c_str());
    EXPECT_EQ(r["curve"], "aces");
    EXPECT_EQ(r["values"], 96 * 96 * 3);
    EXPECT_LE(r["max_diff"].get<int>(), 1) << r.dump();
    EXPECT_LE(r["differ"].get<int>(), 96 * 96 * 3 / 50) << r.dump();
}

// Several viewers at once, each pulling stats and both kinds of image, and one that hangs up in
// the middle of its request: all are answered, the render goes on, and stops cleanly.
TEST(LiveView, SeveralViewersAtOnce) {
    const std::string dir = make_temp_dir("live_many");
    const int port = free_port();
    std::string out;
    int status = -1;
    std::thread render([&] {
        status =
            run_clppm("--integrator sppm --width 64 --height 64 --photons 20000 --passes 100000 --quiet "
                      "--no-png -o " +
                          dir + "/m.exr --stats-json " + dir + "/stats.json --serve 127.0.0.1:" + std::to_string(port),
                      &out);
    });
    {
        httplib::Client c("127.0.0.1", port);
        ASSERT_TRUE(get_when_up(c, "/stats"));
    }
    constexpr int kViewers = 4;
    std::atomic<int> ok{0}, failed{0};
    std::atomic<bool> quit{false};
    std::vector<std::thread> viewers;
    std::vector<int> first_pass(kViewers, -1), last_pass(kViewers, -1);
    for (int v = 0; v < kViewers; ++v)
        viewers.emplace_back([&, v] {
            httplib::Client c("127.0.0.1", port);
            for (int i = 0; !quit; ++i) {
                auto s = c.Get("/stats");
                if (!s || s->status != 200) {
                    ++failed; // the render has ended, say
                    std::this_thread::sleep_for(std::chrono::milliseconds(50));
                    continue;
                }
                const nlohmann::json j = nlohmann::json::parse(s->body);
                const int pass = j["progress"].value("pass", 0);
                if (first_pass[v] < 0 && pass > 0) first_pass[v] = pass;
                last_pass[v] = pass;
                if (j["version"].get<int>() > 0) {
                    auto img = c.Get(i % 2 ? "/image.png" : "/image.f16");
                    (img && img->status == 200 ? ok : failed)++;
                }
                std::this_thread::sleep_for(std::chrono::milliseconds(50));
            }
        });
    // A viewer that sends half a request and hangs up.
    for (int i = 0; i < 3; ++i) {
        const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
        sockaddr_in a{};
        a.sin_family = AF_INET;
        a.sin_port = htons(uint16_t(port));
        a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0) {
            const char half[] = "GET /image.f16 HTTP/1.1\r\nHost: 127.0";
            (void)!::write(fd, half, sizeof half - 1);
        }
        ::close(fd);
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
    }
    // Until every viewer has seen the render advance by a few passes.
    for (int i = 0; i < 600; ++i) {
        bool all = true;
        for (int v = 0; v < kViewers; ++v) all = all && first_pass[v] > 0 && last_pass[v] >= first_pass[v] + 3;
        if (all) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    {
        httplib::Client c("127.0.0.1", port);
        auto r = c.Post("/stop", "", "text/plain");
        ASSERT_TRUE(r);
        EXPECT_EQ(r->status, 202);
    }
    render.join();
    quit = true;
    for (auto& t : viewers) t.join();
    EXPECT_EQ(status, 0) << out;
    for (int v = 0; v < kViewers; ++v)
        EXPECT_GE(last_pass[v], first_pass[v] + 3)
            << "viewer " << v << " saw passes " << first_pass[v] << ".." << last_pass[v];
    std::printf("%d images served to %d viewers\n", ok.load(), kViewers);
    EXPECT_GE(ok.load(), 4 * kViewers);
    std::ifstream js(dir + "/stats.json");
    EXPECT_EQ(nlohmann::json::parse(js)["live_view"]["stopped_it"], true);
}

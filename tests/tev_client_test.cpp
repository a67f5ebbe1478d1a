// --display-server: the bytes of tev's packets, written out here from the protocol as tev's own
// client documents it (src/python/ipc.py in tev: a little-endian uint32 length of the whole
// packet, a type byte, then the fields; strings end in a 0 byte), and a render sending to a
// listening socket: CreateImage once, then UpdateImage tiles whose last full image is the EXR.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <netinet/in.h>
#include <sys/socket.h>
#include <thread>
#include <unistd.h>
#include <utility>

#include "io/image_io.h"
#include "render/tev_client.h"
#include "test_util.h"
#include "util/error.h"

using namespace clppm;
using namespace clppm::test;

namespace {

std::string bytes(std::initializer_list<int> v) {
    std::string s;
    for (int b : v) s.push_back(char(b));
    return s;
}

// A socket listening on a free loopback port, standing in for tev: (fd, port), fd < 0 on failure.
// `receive_buffer` > 0 sets SO_RCVBUF, which accepted connections inherit.
std::pair<int, int> listen_on_loopback(int receive_buffer = 0) {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    if (receive_buffer > 0) ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &receive_buffer, sizeof receive_buffer);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof a;
    if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || ::listen(fd, 1) != 0 ||
        ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0) {
        ::close(fd);
        return {-1, 0};
    }
    return {fd, ntohs(a.sin_port)};
}

uint32_t u32(const std::string& s, size_t at) {
    uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | uint8_t(s[at + size_t(i)]);
    return v;
}

} // namespace

TEST(Tev, CreateImagePacketIsTheProtocolsBytes) {
    const std::string expected = bytes({30,  0,   0,   0,                       // length of the whole packet
                                        4,                                      // CreateImage
                                        1,                                      // grab focus
                                        'a', '.', 'e', 'x', 'r', 0, 2, 0, 0, 0, // width
                                        1,   0,   0,   0,                       // height
                                        3,   0,   0,   0,                       // channels
                                        'R', 0,   'G', 0,   'B', 0});
    EXPECT_EQ(tev::create_image_packet("a.exr", 2, 1, true), expected);
}

TEST(Tev, UpdateImagePacketIsTheProtocolsBytes) {
    Image img;
    img.width = 2, img.height = 1;
    img.rgb = {1.f, 2.f, 0.5f, 0.f, -0.f, 4.f};
    std::string expected =
        bytes({0,   0, 0,    0,            // length, below
               6,                          // UpdateImage version 3
               0,                          // grab focus
               'a', 0,                     // name
               3,   0, 0,    0,            // channels
               'R', 0, 'G',  0,    'B', 0, // their names
               1,   0, 0,    0,            // x
               0,   0, 0,    0,            // y
               1,   0, 0,    0,            // width
               1,   0, 0,    0,            // height
               0,   0, 0,    0,    0,   0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 0, 0, 0, 0, // offsets 0, 1, 2
               3,   0, 0,    0,    0,   0, 0, 0, 3, 0, 0, 0, 0, 0, 0, 0, 3, 0, 0, 0, 0, 0, 0, 0, // strides 3, 3, 3
               0,   0, 0,    0,                                                                  // 0.0f
               0,   0, 0,    0x80,                                                               // -0.0f
               0,   0, 0x80, 0x40});                                                             // 4.0f
    expected[0] = char(expected.size());
    EXPECT_EQ(tev::update_image_packet("a", img, 1, 0, 1, 1), expected);
}

TEST(Tev, BadAddressesAreOneLineErrors) {
    for (const char* bad : {"nohost", ":14158", "localhost:", "localhost:x", "localhost:70000"}) {
        try {
            TevClient c(bad, "x");
            ADD_FAILURE() << bad;
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()).rfind(std::string("--display-server ") + bad + ": must be HOST:PORT", 0),
                      0u)
                << e.what();
        }
    }
    // A port nobody listens on.
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
    socklen_t len = sizeof a;
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
    const int port = ntohs(a.sin_port);
    ::close(fd);
    try {
        TevClient c("127.0.0.1:" + std::to_string(port), "x");
        ADD_FAILURE() << "connected to nothing";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("nothing listens there"), std::string::npos) << e.what();
    }
}

// A render sends to a socket standing in for tev: the stream is CreateImage (40 x 24, R G B) and
// then UpdateImage tiles; the last update of each pixel is the final EXR's value, bit for bit.
TEST(Tev, ARenderSendsItsImage) {
    const auto [server, port] = listen_on_loopback();
    ASSERT_GE(server, 0);
    std::string stream;
    std::thread reader([&] {
        const int c = ::accept(server, nullptr, nullptr);
        char buf[65536];
        for (ssize_t n; (n = ::read(c, buf, sizeof buf)) > 0;) stream.append(buf, size_t(n));
        ::close(c);
    });
    const std::string dir = make_temp_dir("tev");
    std::string out;
    EXPECT_EQ(run_clppm("--width 40 --height 24 --passes 3 --quiet --no-png -o " + dir +
                            "/t.exr --display-server 127.0.0.1:" + std::to_string(port),
                        &out),
              0)
        << out;
    reader.join();
    ::close(server);
    const Image img = read_exr(dir + "/t.exr");
    ASSERT_GE(stream.size(), 5u);
    // Walk the packets.
    std::vector<float> last(img.rgb.size(), -1.f);
    size_t at = 0, creates = 0, updates = 0;
    while (at + 5 <= stream.size()) {
        const uint32_t n = u32(stream, at);
        ASSERT_GE(n, 5u);
        ASSERT_LE(at + n, stream.size());
        const std::string p = stream.substr(at, n);
        if (p[4] == 4) {
            ++creates;
            EXPECT_EQ(p, tev::create_image_packet("t.exr", 40, 24, true));
        } else {
            ASSERT_EQ(p[4], 6);
            ++updates;
            size_t q = 6 + std::strlen(&p[6]) + 1 + 4 + 6; // name, channel count, "R\0G\0B\0"
            const int x = int(u32(p, q)), y = int(u32(p, q + 4)), w = int(u32(p, q + 8)), h = int(u32(p, q + 12));
            q += 16 + 48;
            ASSERT_EQ(p.size(), q + size_t(w) * size_t(h) * 12);
            for (int r = 0; r < h; ++r)
                for (int c = 0; c < w; ++c)
                    std::memcpy(&last[(size_t(y + r) * 40 + size_t(x + c)) * 3],
                                &p[q + (size_t(r) * size_t(w) + size_t(c)) * 12], 12);
        }
        at += n;
    }
    EXPECT_EQ(at, stream.size());
    EXPECT_EQ(creates, 1u);
    EXPECT_GE(updates, 1u);
    EXPECT_TRUE(last == img.rgb) << "tev's last image is not the EXR";
}

// A viewer that accepts the connection and then reads nothing (it held a render for good before:
// 126 s until killed) costs frames, never time: the render ends as it would unwatched, with one
// warning naming the viewer. The command runs under a timeout, so that a regression fails here
// instead of hanging the suite.
TEST(Tev, AViewerThatNeverReadsDoesNotHoldTheRenderBack) {
    // A receive window of a few kilobytes: the sender's buffer fills fast.
    const auto [server, port] = listen_on_loopback(4096);
    ASSERT_GE(server, 0);
    int client = -1;
    std::thread acceptor([&] { client = ::accept(server, nullptr, nullptr); }); // and never read
    const std::string dir = make_temp_dir("tev_stall");
    const std::string args =
        "--width 384 --height 384 --passes 24 --photons 20000 --quiet --no-png -o " + dir + "/t.exr";
    std::string out;
    const auto t0 = std::chrono::steady_clock::now();
    ASSERT_EQ(run_command("timeout 120 " + clppm_binary() + " " + args +
                              " --display-server 127.0.0.1:" + std::to_string(port),
                          &out),
              0)
        << out;
    const double watched = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    acceptor.join();
    size_t warnings = 0;
    for (size_t p = out.find("clppm: warning: --display-server"); p != std::string::npos;
         p = out.find("clppm: warning: --display-server", p + 1))
        ++warnings;
    EXPECT_EQ(warnings, 1u) << out;
    // Whichever comes first: the sender's stall limit, or the final image's wait.
    EXPECT_TRUE(out.find("the viewer has read nothing for 2 s; no more updates") != std::string::npos ||
                out.find("the viewer did not take the last image within 2 s") != std::string::npos)
        << out;
    ASSERT_EQ(run_clppm(args, &out), 0) << out;
    const double unwatched = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() - watched;
    std::printf("never-reading viewer: %.1f s watched, %.1f s unwatched\n", watched, unwatched);
    // The stall is noticed within TevClient::kStallSeconds and the last image waits at most
    // kFinalFlushSeconds: a few seconds over the unwatched render, on a busy machine too.
    EXPECT_LT(watched, unwatched + 20.0);
    ::close(client);
    ::close(server);
}

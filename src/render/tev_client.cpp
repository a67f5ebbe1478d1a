#include "render/tev_client.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include "util/error.h"
#include "util/steady_seconds.h"

namespace clppm {

namespace tev {

namespace {

void put_u8(std::string& b, uint8_t v) { b.push_back(char(v)); }
void put_i32(std::string& b, int32_t v) {
    for (int i = 0; i < 4; ++i) b.push_back(char((uint32_t(v) >> (8 * i)) & 0xff));
}
void put_i64(std::string& b, int64_t v) {
    for (int i = 0; i < 8; ++i) b.push_back(char((uint64_t(v) >> (8 * i)) & 0xff));
}
void put_f32(std::string& b, float v) {
    uint32_t u;
    std::memcpy(&u, &v, 4);
    put_i32(b, int32_t(u));
}
void put_str(std::string& b, const std::string& s) {
    b += s;
    b.push_back('\0');
}
// The length field: the whole packet, itself included.
std::string finish(std::string b) {
    const uint32_t n = uint32_t(b.size());
    for (int i = 0; i < 4; ++i) b[size_t(i)] = char((n >> (8 * i)) & 0xff);
    return b;
}

const char* const kChannels[3] = {"R", "G", "B"};

} // namespace

std::string create_image_packet(const std::string& name, int width, int height, bool grab_focus) {
    std::string b(4, '\0');
    put_u8(b, 4); // CreateImage
    put_u8(b, grab_focus ? 1 : 0);
    put_str(b, name);
    put_i32(b, width);
    put_i32(b, height);
    put_i32(b, 3);
    for (const char* c : kChannels) put_str(b, c);
    return finish(std::move(b));
}

std::string update_image_packet(const std::string& name, const Image& img, int x, int y, int w, int h) {
    std::string b(4, '\0');
    put_u8(b, 6); // UpdateImage, version 3
    put_u8(b, 0); // grab focus
    put_str(b, name);
    put_i32(b, 3);
    for (const char* c : kChannels) put_str(b, c);
    put_i32(b, x);
    put_i32(b, y);
    put_i32(b, w);
    put_i32(b, h);
    for (int c = 0; c < 3; ++c) put_i64(b, c); // channel c starts at float c
    for (int c = 0; c < 3; ++c) put_i64(b, 3); // and steps 3 floats per pixel
    b.reserve(b.size() + size_t(w) * size_t(h) * 12);
    for (int row = y; row < y + h; ++row)
        for (int col = x; col < x + w; ++col)
            for (int c = 0; c < 3; ++c)
                put_f32(b, img.rgb[(size_t(row) * size_t(img.width) + size_t(col)) * 3 + size_t(c)]);
    return finish(std::move(b));
}

} // namespace tev

namespace {

// Connects a non-blocking socket to `a` within `seconds`; -1 when it cannot.
int connect_within(const addrinfo* a, double seconds) {
    const int fd = ::socket(a->ai_family, a->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0) return -1;
    if (::connect(fd, a->ai_addr, a->ai_addrlen) == 0) return fd;
    if (errno == EINPROGRESS) {
        pollfd p{fd, POLLOUT, 0};
        int err = 0;
        socklen_t len = sizeof err;
        if (::poll(&p, 1, int(seconds * 1000)) == 1 && ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &len) == 0 &&
            err == 0)
            return fd;
    }
    ::close(fd);
    return -1;
}

} // namespace

TevClient::TevClient(const std::string& address, std::string image_name)
    : address_(address), name_(std::move(image_name)) {
    const size_t colon = address.rfind(':');
    const std::string host = colon == std::string::npos ? std::string() : address.substr(0, colon);
    const std::string port = colon == std::string::npos ? std::string() : address.substr(colon + 1);
    char* end = nullptr;
    const long p = port.empty() ? -1 : std::strtol(port.c_str(), &end, 10);
    if (host.empty() || port.empty() || *end != '\0' || p < 1 || p > 65535)
        throw Error("--display-server " + address + ": must be HOST:PORT (tev listens on 127.0.0.1:14158)");
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    addrinfo* found = nullptr;
    if (getaddrinfo(host.c_str(), port.c_str(), &hints, &found) != 0 || !found)
        throw Error("--display-server " + address + ": unknown host " + host);
    for (addrinfo* a = found; a && fd_ < 0; a = a->ai_next) fd_ = connect_within(a, kConnectSeconds);
    freeaddrinfo(found);
    if (fd_ < 0) throw Error("--display-server " + address + ": nothing listens there (is tev running?)");
    thread_ = std::thread([this] { run(); });
}

TevClient::~TevClient() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
    if (fd_ >= 0) ::close(fd_);
}

void TevClient::fail(const std::string& why) {
    gone_ = true;
    std::lock_guard<std::mutex> lock(mutex_);
    if (!warned_) warning_ = "--display-server " + address_ + ": " + why + "; no more updates";
    warned_ = true;
}

std::string TevClient::take_warning() {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::move(warning_);
}

// Waits for the socket in slices, so that the destructor is answered within one; gives up on a
// viewer that took nothing for kStallSeconds.
bool TevClient::write_all(const std::string& bytes) {
    size_t done = 0;
    double last_progress = steady_seconds();
    while (done < bytes.size()) {
        const ssize_t n = ::send(fd_, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL);
        if (n > 0) {
            done += size_t(n);
            last_progress = steady_seconds();
            continue;
        }
        if (n < 0 && errno == EINTR) continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            {
                std::lock_guard<std::mutex> lock(mutex_);
                if (stop_) return false;
            }
            if (steady_seconds() - last_progress > kStallSeconds) {
                char why[120];
                std::snprintf(why, sizeof why, "the viewer has read nothing for %.0f s", kStallSeconds);
                fail(why);
                return false;
            }
            pollfd p{fd_, POLLOUT, 0};
            ::poll(&p, 1, 50);
            continue;
        }
        fail(std::string("the connection is gone (") + std::strerror(errno) + ")");
        return false;
    }
    return true;
}

void TevClient::run() {
    for (;;) {
        std::unique_ptr<Image> img;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [&] { return stop_ || pending_; });
            if (stop_) return;
            img = std::move(pending_);
            sending_ = true;
        }
        bool ok = true;
        if (img->width != width_ || img->height != height_) {
            ok = write_all(tev::create_image_packet(name_, img->width, img->height, true));
            if (ok) width_ = img->width, height_ = img->height;
        }
        for (int y = 0; ok && y < img->height; y += tev::kTile)
            for (int x = 0; ok && x < img->width; x += tev::kTile)
                ok = write_all(tev::update_image_packet(name_, *img, x, y, std::min(tev::kTile, img->width - x),
                                                        std::min(tev::kTile, img->height - y)));
        {
            std::lock_guard<std::mutex> lock(mutex_);
            sending_ = false;
        }
        idle_.notify_all();
        if (!ok) return; // gone, stalled or stopping: a torn packet ends the connection
    }
}

void TevClient::send(const Image& img) {
    if (gone_ || img.width <= 0 || img.height <= 0) return;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (pending_) ++dropped_;
        pending_ = std::make_unique<Image>(img);
    }
    wake_.notify_one();
}

bool TevClient::flush(double seconds) {
    std::unique_lock<std::mutex> lock(mutex_);
    const bool idle = idle_.wait_for(lock, std::chrono::duration<double>(seconds),
                                     [&] { return gone_.load() || (!pending_ && !sending_); });
    if (!idle && !warned_) {
        char why[160];
        std::snprintf(why, sizeof why, "--display-server %s: the viewer did not take the last image within %.0f s",
                      address_.c_str(), seconds);
        warning_ = why;
        warned_ = true;
    }
    return idle && !gone_.load();
}

} // namespace clppm

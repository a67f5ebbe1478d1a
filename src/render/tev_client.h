// --display-server HOST:PORT: the render's image sent to the tev viewer in its network protocol,
// as pbrt-v4's --display-server does. Each packet is a little-endian uint32 of its whole length,
// a type byte and its payload: CreateImage (type 4: grab focus, the name, width, height, channel
// count and names) once, then UpdateImage version 3 (type 6: grab focus, the name, channel count
// and names, x, y, width, height, an int64 offset and stride per channel into the float data
// that follows) for each tile of at most kTile x kTile pixels. Strings are UTF-8 with a 0 byte.
#pragma once
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "io/image_io.h"

namespace clppm {

namespace tev {

constexpr int kTile = 128;

// The packets' bytes, for the client and for the test that checks them against the protocol.
std::string create_image_packet(const std::string& name, int width, int height, bool grab_focus);
// The tile [x, x + w) x [y, y + h) of `img` as R, G, B, interleaved.
std::string update_image_packet(const std::string& name, const Image& img, int x, int y, int w, int h);

} // namespace tev

// A connection to tev. A viewer never holds a render back: send() hands the image to a sender
// thread and returns at once; an image still waiting when a newer one comes is dropped for it, so
// a slow or stalled viewer costs frames, never time. A viewer that goes away, or stops reading for
// kStallSeconds, is said once; the render goes on.
class TevClient {
public:
    static constexpr double kConnectSeconds = 5.0; // to connect at all
    static constexpr double kStallSeconds = 2.0;   // without progress on a frame: the viewer is not reading

    // "HOST:PORT"; throws clppm::Error naming --display-server when it is malformed or nothing
    // listens there (within kConnectSeconds).
    TevClient(const std::string& address, std::string image_name);
    ~TevClient();
    TevClient(const TevClient&) = delete;
    TevClient& operator=(const TevClient&) = delete;

    // Queues the whole image (CreateImage first, and again when the size changes), in tiles.
    void send(const Image& img);
    // Waits at most `seconds` until what was queued has gone out; false when it has not (the
    // viewer is not reading, or is gone: take_warning() then says so).
    bool flush(double seconds);
    bool connected() const { return !gone_.load(); }
    // The one warning about this viewer, once ("" when there is nothing to say): taken by the
    // render thread, which says it.
    std::string take_warning();
    // Frames replaced by a newer one before they went out.
    uint64_t dropped() const { return dropped_.load(); }

private:
    void run();
    bool write_all(const std::string& bytes);
    void fail(const std::string& why);

    std::string address_, name_;
    int fd_ = -1;
    int width_ = 0, height_ = 0; // of the image tev holds (sender thread)
    std::mutex mutex_;
    std::condition_variable wake_, idle_;
    std::unique_ptr<Image> pending_;
    bool sending_ = false, stop_ = false;
    std::atomic<bool> gone_{false};
    std::atomic<uint64_t> dropped_{0};
    std::string warning_;
    bool warned_ = false;
    std::thread thread_;
};

} // namespace clppm

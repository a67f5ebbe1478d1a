// --display-server HOST:PORT: the render's image sent to the tev viewer in its network protocol,
// as pbrt-v4's --display-server does. Each packet is a little-endian uint32 of its whole length,
// a type byte and its payload: CreateImage (type 4: grab focus, the name, width, height, channel
// count and names) once, then UpdateImage version 3 (type 6: grab focus, the name, channel count
// and names, x, y, width, height, an int64 offset and stride per channel into the float data
// that follows) for each tile of at most kTile x kTile pixels. Strings are UTF-8 with a 0 byte.
#pragma once
#include <cstdint>
#include <string>
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

// A connection to tev. Sending never throws: a viewer that goes away turns the client off with a
// warning, and the render goes on.
class TevClient {
public:
    // "HOST:PORT"; throws clppm::Error naming --display-server when it is malformed or nothing
    // listens there.
    TevClient(const std::string& address, std::string image_name);
    ~TevClient();
    TevClient(const TevClient&) = delete;
    TevClient& operator=(const TevClient&) = delete;

    // The whole image, in tiles (CreateImage first, and again when the size changes).
    void send(const Image& img);
    bool connected() const { return fd_ >= 0; }

private:
    bool write_all(const std::string& bytes);

    std::string address_, name_;
    int fd_ = -1;
    int width_ = 0, height_ = 0; // of the image tev holds
};

} // namespace clppm

#include "integrators/film.h"

#include <vector>

#include "device/kernel_launch.h"

namespace clppm {

Image read_film(const DeviceContext& dc, const cl::Buffer& buffer, unsigned width, unsigned height) {
    const std::vector<cl_float4> px = read_buffer<cl_float4>(dc.queue, buffer, size_t(width) * height);
    Image img;
    img.width = int(width);
    img.height = int(height);
    img.rgb.resize(px.size() * 3);
    for (size_t i = 0; i < px.size(); ++i)
        for (int c = 0; c < 3; ++c) img.rgb[3 * i + c] = px[i].s[c];
    return img;
}

} // namespace clppm

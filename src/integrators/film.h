// The film: the float4 image buffer a film kernel (kernels/film.cl, sppm.cl, path_trace.cl)
// writes, read back into an Image.
#pragma once
#include <cstddef>

#include "device/cl.h"
#include "device/device.h"
#include "io/image_io.h"

namespace clppm {

constexpr size_t kFilmBytesPerPixel = sizeof(cl_float4);

Image read_film(const DeviceContext& dc, const cl::Buffer& buffer, unsigned width, unsigned height);

} // namespace clppm

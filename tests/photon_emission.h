// Photons straight from the lights (kernels/lights.cl's emit_photon), for the tests of emission:
// the wrapper kernel to append to a test program, and the host call that runs it.
#pragma once
#include <vector>

#include "device/device.h"
#include "scene/device_scene.h"
#include "test_util.h"

namespace clppm::test {

// emit_many: photon i of `seed` as 9 floats, origin, direction, flux.
inline const char* kEmitManyKernel = R"CL(
__kernel void emit_many(SCENE_PARAMS, ulong seed, __global float* out) {
    uint i = get_global_id(0);
    Rng rng = rng_make(seed, 1, i, RNG_PHOTON);
    float3 org, dir, flux;
    emit_photon(SCENE_ARGS, &rng, &org, &dir, &flux);
    __global float* o = &out[9 * (size_t)i];
    o[0] = org.x; o[1] = org.y; o[2] = org.z;
    o[3] = dir.x; o[4] = dir.y; o[5] = dir.z;
    o[6] = flux.x; o[7] = flux.y; o[8] = flux.z;
}
)CL";

constexpr size_t kEmittedFloats = 9; // floats per photon: origin, direction, flux

// n photons of `seed` from a program holding kEmitManyKernel.
inline std::vector<float> emit_photons(const DeviceContext& dc, const DeviceScene& ds, const cl::Program& program,
                                       uint64_t seed, size_t n) {
    cl::Buffer out(dc.context, CL_MEM_WRITE_ONLY, kEmittedFloats * n * sizeof(float));
    cl::Kernel k(program, "emit_many");
    int a = ds.set_scene_args(k);
    k.setArg(a++, cl_ulong(seed)), k.setArg(a++, out);
    dc.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(n));
    return read_buffer<float>(dc, out, kEmittedFloats * n);
}

} // namespace clppm::test

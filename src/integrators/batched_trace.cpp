#include "integrators/batched_trace.h"
#include "device/kernel_launch.h"

#include <algorithm>
#include <cstdlib>

#include "util/error.h"

namespace clppm {

namespace {

constexpr uint64_t kMinCapacity = 1024;

uint64_t capacity_budget(size_t record_bytes, const DeviceInfo& device) {
    return std::min<uint64_t>(
        {device.max_alloc / record_bytes, device.global_mem / 4 / (2 * record_bytes), 0x7fffffffu});
}

} // namespace

uint64_t BatchedTrace::initial_capacity(uint64_t items, uint64_t records_per_item, size_t record_bytes,
                                        const DeviceInfo& device) {
    return std::clamp<uint64_t>(items * records_per_item, kMinCapacity,
                                std::max<uint64_t>(kMinCapacity, capacity_budget(record_bytes, device)));
}

BatchedTrace::BatchedTrace(const DeviceContext& dc, size_t record_bytes, uint64_t records_per_item, uint64_t max_batch,
                           std::string item, std::string record)
    : dc_(dc), record_bytes_(record_bytes), per_item_(records_per_item), item_(std::move(item)),
      record_(std::move(record)), max_capacity_(capacity_budget(record_bytes, dc.info)) {
    uint64_t batch = max_batch;
    if (const char* e = std::getenv("CLPPM_PHOTON_BATCH"); e && *e)
        batch = std::min<uint64_t>(batch, std::strtoull(e, nullptr, 10));
    batch = std::min<uint64_t>(batch, max_capacity_ / per_item_);
    batch_ = uint32_t(std::clamp<uint64_t>(batch, 1, 0x7fffffffu));
    counter_ = make_buffer(dc.context, CL_MEM_READ_WRITE, sizeof(cl_uint));
}

BatchedTrace::~BatchedTrace() {
    try {
        dc_.queue.finish();
    } catch (const cl::Error&) { // a lost device: nothing left to wait for
    }
}

void BatchedTrace::allocate(uint32_t capacity) {
    capacity_ = capacity;
    records_ = make_buffer(dc_.context, CL_MEM_READ_WRITE, size_t(capacity) * record_bytes_);
    sorted_ = make_buffer(dc_.context, CL_MEM_READ_WRITE, size_t(capacity) * record_bytes_);
}

void BatchedTrace::ensure_allocated() {
    if (capacity_ == 0) allocate(uint32_t(initial_capacity(batch_, per_item_, record_bytes_, dc_.info)));
}

bool BatchedTrace::read_stored() {
    cl_uint stored = 0;
    dc_.queue.enqueueReadBuffer(counter_, CL_TRUE, 0, sizeof(cl_uint), &stored);
    stored_ = stored;
    if (stored <= capacity_) return true;
    const uint64_t want = uint64_t(stored) * 5 / 4 + kMinCapacity;
    if (want <= max_capacity_) allocate(uint32_t(want));
    else if (batch_ > 1) batch_ = std::max<uint32_t>(1, batch_ / 2);
    else throw Error(item_ + " stores more " + record_ + " than the device memory budget allows");
    return false;
}

} // namespace clppm

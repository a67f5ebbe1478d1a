// The records a pass traces (photons, VCM's light vertices) and the loop that traces them in
// batches, shared by every integrator that traces from the lights. The records of a batch live in
// two device buffers (as traced, and sorted into the hashed grid) within a budget: both within a
// quarter of the device's memory, each within its largest allocation. A batch whose records
// overflow the buffers grows them within the budget, or else is halved, and is traced again: the
// same items give the same records, so batches never change the image. Between batches the loop
// answers a stop request (util/cancellation.h), which abandons the pass.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "device/cl.h"
#include "device/device.h"
#include "device/kernel_launch.h"
#include "util/cancellation.h"

namespace clppm {

class BatchedTrace {
public:
    // Records of `record_bytes` each; the buffers start out sized for `records_per_item` per item
    // of a batch of at most `max_batch` items (CLPPM_PHOTON_BATCH lowers it, for tests). `item`
    // names an item and `record` a record in the message of an item that alone overflows the
    // budget ("a single photon stores more hits than ...").
    BatchedTrace(const DeviceContext& dc, size_t record_bytes, uint64_t records_per_item, uint64_t max_batch,
                 std::string item, std::string record);
    // Waits for the device queue: non-blocking commands may still use the buffers.
    ~BatchedTrace();
    BatchedTrace(const BatchedTrace&) = delete;
    BatchedTrace& operator=(const BatchedTrace&) = delete;

    // Items [first, end) in batches: trace(first, count) enqueues the kernel that writes up to
    // capacity() records to records() and counts them in counter() (reset to 0 before); once they
    // fit, use(first, count, stored) builds on them.
    template <class Trace, class Use>
    void run(uint32_t first, uint32_t end, Trace trace, Use use) {
        ensure_allocated();
        while (first < end) {
            throw_if_cancelled(); // the statistics still hold the last complete pass
            const uint32_t count = std::min(batch_, end - first);
            fill_buffer(dc_.queue, counter_, cl_uint(0), 0, sizeof(cl_uint));
            trace(first, count);
            if (!read_stored()) continue; // grown or halved: the same items again
            use(first, count, stored_);
            first += count;
        }
    }

    const cl::Buffer& records() const { return records_; }
    const cl::Buffer& sorted() const { return sorted_; }
    const cl::Buffer& counter() const { return counter_; }
    uint32_t capacity() const { return capacity_; }
    uint32_t batch() const { return batch_; } // items per batch at most (it only shrinks)
    size_t device_bytes() const { return 2 * size_t(capacity_) * record_bytes_; }

    // Records the buffers start out with for batches of `items` items, and their bytes (both
    // buffers), for the memory estimate before anything is allocated.
    static uint64_t initial_capacity(uint64_t items, uint64_t records_per_item, size_t record_bytes,
                                     const DeviceInfo& device);

private:
    void ensure_allocated();
    void allocate(uint32_t capacity);
    // Reads the count; false when it overflowed (the buffers grew, or the batch halved).
    bool read_stored();

    const DeviceContext& dc_;
    size_t record_bytes_;
    uint64_t per_item_;
    std::string item_, record_;
    uint64_t max_capacity_; // records the memory budget allows
    uint32_t batch_;        // items per batch
    uint32_t capacity_ = 0;
    uint32_t stored_ = 0;
    cl::Buffer records_, sorted_, counter_;
};

} // namespace clppm

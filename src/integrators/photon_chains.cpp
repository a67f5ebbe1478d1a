#include "integrators/photon_chains.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "device/kernel_launch.h"
#include "integrators/hash_grid.h"
#include "util/error.h"

namespace clppm {

namespace {

// Cells marked per hit point: up to 125 each (a sphere of radius up to twice the cell's side), in
// a table with room for them at a typical radius (27 each) and few collisions.
uint32_t seen_table_size(uint64_t hitpoints) { return hash_grid_table_size(64 * std::max<uint64_t>(hitpoints, 1)); }

size_t cache_bytes(uint64_t chains) { return size_t(chains) * PHOTON_CHAIN_CACHE * sizeof(dev::Photon); }

} // namespace

PhotonChains::PhotonChains(const DeviceContext& dc, const cl::Program& program, IntegratorStats& stats, uint64_t chains)
    : dc_(dc), stats_(stats), chains_count_(chains) {
    k_mark_ = cl::Kernel(program, "visibility_mark");
    const size_t bytes = size_t(chains) * sizeof(dev::PhotonChain);
    for (cl::Buffer& b : chains_) {
        b = make_buffer(dc.context, CL_MEM_READ_WRITE, bytes);
        fill_buffer(dc.queue, b, cl_uchar(0), 0, bytes); // step 0: no state yet
    }
    for (cl::Buffer& b : cache_) b = make_buffer(dc.context, CL_MEM_READ_WRITE, cache_bytes(chains));
    counts_ = make_buffer(dc.context, CL_MEM_READ_WRITE, CHAIN_COUNTS * sizeof(cl_uint));
    grid_info_ = make_buffer(dc.context, CL_MEM_READ_ONLY, sizeof(dev::GridInfo));
}

size_t PhotonChains::memory_needed(uint64_t chains, uint64_t hitpoints) {
    return 2 * (size_t(chains) * sizeof(dev::PhotonChain) + cache_bytes(chains)) + seen_table_size(hitpoints);
}

size_t PhotonChains::device_bytes() const {
    return 2 * (size_t(chains_count_) * sizeof(dev::PhotonChain) + cache_bytes(chains_count_)) + table_size_ +
           sizeof(dev::GridInfo);
}

void PhotonChains::mark(const cl::Buffer& hitpoints, const cl::Buffer& hit_stats, uint32_t n, float global_r2,
                        const float origin[3], double cell) {
    if (table_size_ == 0) { // the first pass fixes the cells; later passes add to the marks
        table_size_ = seen_table_size(n);
        seen_ = make_buffer(dc_.context, CL_MEM_READ_WRITE, table_size_);
        grid_ = dev::GridInfo{};
        for (int k = 0; k < 3; ++k) grid_.origin[k] = origin[k];
        grid_.inv_cell = float(1.0 / cell);
        grid_.table_size = table_size_;
        grid_.num_photons = n;
        dc_.queue.enqueueWriteBuffer(grid_info_, CL_TRUE, 0, sizeof grid_, &grid_);
        fill_buffer(dc_.queue, seen_, cl_uchar(0), 0, table_size_);
    }
    if (n == 0) return;
    set_args(k_mark_, 0, grid_info_, hitpoints, hit_stats, cl_uint(n), cl_float(global_r2), seen_);
    cl::Event ev;
    enqueue_1d(dc_.queue, k_mark_, n, &ev);
    add_event_time(stats_, "visibility_mark", ev);
}

void PhotonChains::set_trace_args(cl::Kernel& kernel, int a, uint32_t photons_per_pass) {
    fill_buffer(dc_.queue, counts_, cl_uint(0), 0, CHAIN_COUNTS * sizeof(cl_uint));
    set_args(kernel, a, grid_info_, seen_, chains_[current_], chains_[1 - current_], cache_[current_],
             cache_[1 - current_], counts_, cl_uint(photons_per_pass));
}

void PhotonChains::commit_batch() {
    cl_uint c[CHAIN_COUNTS];
    dc_.queue.enqueueReadBuffer(counts_, CL_TRUE, 0, sizeof c, c);
    for (int k = 0; k < CHAIN_COUNTS; ++k) pending_[k] += c[k];
}

void PhotonChains::end_pass() {
    current_ = 1 - current_;
    for (int k = 0; k < CHAIN_COUNTS; ++k) stats_.chain_counts[k] += pending_[k], pending_[k] = 0;
}

void PhotonChains::begin_pass() {
    for (uint64_t& p : pending_) p = 0; // a pass abandoned between batches (Ctrl-C) counts nothing
}

double PhotonChains::effective_emitted(uint64_t uniform_paths) const {
    const uint64_t visible = stats_.chain_counts[CHAIN_UNIFORM_VISIBLE];
    if (visible == 0) return std::numeric_limits<double>::infinity();
    return double(stats_.chain_counts[CHAIN_STATES]) * (double(uniform_paths) / double(visible));
}

void PhotonChains::save(Checkpoint& ck) const {
    ck.put("photon_chains", read_buffer<dev::PhotonChain>(dc_.queue, chains_[current_], chains_count_));
    ck.put("photon_chain_cache",
           read_buffer<dev::Photon>(dc_.queue, cache_[current_], chains_count_ * PHOTON_CHAIN_CACHE));
    ck.put("photon_seen_cells", read_buffer<unsigned char>(dc_.queue, seen_, table_size_));
    ck.header["photon_seen_grid"] = {grid_.origin[0], grid_.origin[1],  grid_.origin[2],
                                     grid_.inv_cell,  grid_.table_size, grid_.num_photons};
    Json counts = Json::array();
    for (uint64_t c : stats_.chain_counts) counts.push_back(c);
    ck.header["photon_chain_counts"] = counts;
}

void PhotonChains::restore(const Checkpoint& ck) {
    const Json& h = ck.header;
    if (!h.contains("photon_chain_counts") || !h["photon_chain_counts"].is_array() ||
        h["photon_chain_counts"].size() != CHAIN_COUNTS)
        throw Error(ck.path + ": checkpoint lacks the photon chains' counts (photon_chain_counts)");
    for (int k = 0; k < CHAIN_COUNTS; ++k) {
        const Json& v = h["photon_chain_counts"][size_t(k)];
        if (!v.is_number_unsigned())
            throw Error(ck.path + ": checkpoint has photon_chain_counts[" + std::to_string(k) + "] = " + v.dump());
        stats_.chain_counts[k] = v.get<uint64_t>();
    }
    const Json& g = h.contains("photon_seen_grid") ? h["photon_seen_grid"] : Json();
    bool grid_ok = g.is_array() && g.size() == 6;
    for (size_t k = 0; grid_ok && k < 6; ++k) grid_ok = g[k].is_number() && std::isfinite(g[k].get<double>());
    if (grid_ok) {
        grid_ = dev::GridInfo{};
        for (int k = 0; k < 3; ++k) grid_.origin[k] = g[size_t(k)].get<float>();
        grid_.inv_cell = g[3].get<float>();
        grid_.table_size = g[4].get<uint32_t>();
        grid_.num_photons = g[5].get<uint32_t>();
        grid_ok = grid_.inv_cell > 0 && grid_.table_size >= 1024 && (grid_.table_size & (grid_.table_size - 1)) == 0 &&
                  grid_.table_size <= (1u << 31);
    }
    if (!grid_ok) throw Error(ck.path + ": checkpoint lacks the photon chains' cells (photon_seen_grid)");
    table_size_ = grid_.table_size;
    seen_ = make_buffer(dc_.context, CL_MEM_READ_WRITE, table_size_);
    write_buffer(dc_.queue, seen_, ck.get<unsigned char>("photon_seen_cells", table_size_));
    dc_.queue.enqueueWriteBuffer(grid_info_, CL_TRUE, 0, sizeof grid_, &grid_);
    std::vector<dev::PhotonChain> chains = ck.get<dev::PhotonChain>("photon_chains", chains_count_);
    for (const dev::PhotonChain& c : chains) {
        bool ok =
            c.step >= 0.f && c.step <= 1.f && (c.cached <= PHOTON_CHAIN_CACHE || c.cached == PHOTON_CHAIN_UNCACHED);
        for (float u : c.u) ok = ok && u >= 0.f && u < 1.f;
        if (!ok) throw Error(ck.path + ": checkpoint has a photon chain out of range (photon_chains)");
    }
    write_buffer(dc_.queue, chains_[current_], chains);
    write_buffer(dc_.queue, cache_[current_],
                 ck.get<dev::Photon>("photon_chain_cache", chains_count_ * PHOTON_CHAIN_CACHE));
}

} // namespace clppm

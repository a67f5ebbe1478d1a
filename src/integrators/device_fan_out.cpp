#include "integrators/device_fan_out.h"

#include <algorithm>
#include <exception>
#include <thread>

#include "util/cancellation.h"
#include "util/steady_seconds.h"

namespace clppm {

DeviceFanOut::DeviceFanOut(const std::vector<unsigned>& compute_units) {
    for (unsigned cu : compute_units) rate_.push_back(std::max(1u, cu));
}

std::vector<uint32_t> DeviceFanOut::split(uint32_t total) const {
    double sum = 0;
    for (double r : rate_) sum += r;
    std::vector<uint32_t> s(rate_.size(), 0);
    uint32_t given = 0;
    for (size_t k = 1; k < s.size(); ++k) given += s[k] = uint32_t(double(total) * rate_[k] / sum);
    s[0] = total - given;
    return s;
}

void DeviceFanOut::run(uint32_t first, const std::vector<uint32_t>& shares,
                       const std::function<void(size_t, uint32_t, uint32_t)>& work) {
    const size_t n = shares.size();
    std::vector<double> seconds(n, 0.0);
    std::vector<std::exception_ptr> errors(n);
    const CancelToken* token = current_cancel_token(); // a cancel of this render reaches every device's share
    auto one = [&](size_t k, uint32_t begin) {
        const CancelScope scope(token);
        try {
            const double t0 = steady_seconds();
            work(k, begin, shares[k]);
            seconds[k] = steady_seconds() - t0;
        } catch (...) {
            errors[k] = std::current_exception();
        }
    };
    std::vector<std::thread> threads;
    uint32_t at = first + shares[0];
    for (size_t k = 1; k < n; ++k) {
        threads.emplace_back(one, k, at);
        at += shares[k];
    }
    one(0, first);
    for (std::thread& t : threads) t.join();
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);
    for (size_t k = 0; k < n; ++k)
        if (shares[k] > 0 && seconds[k] > 0) rate_[k] = 0.5 * rate_[k] + 0.5 * double(shares[k]) / seconds[k];
}

} // namespace clppm

// How to share a pass between processes of different speed (device/cluster.h) so that they
// finish together. A process's time for c units of work (photons, or pixels) is modelled as
// t = a + b c: a fixed part that does not shrink with its share (the gather over every hit point,
// the grid, the reduction's readback) and a part per unit. Sharing in proportion to units per
// second alone would starve a process whose fixed part is large: a smaller share makes its rate
// look worse, which shrinks its share again. Fitting a and b over the recent passes and solving
// a_r + b_r c_r = T for all r with sum c_r = total shares the work by the marginal cost instead.
#pragma once
#include <cstddef>
#include <cstdint>
#include <deque>
#include <utility>
#include <vector>

namespace clppm {

class WorkBalance {
public:
    static constexpr size_t kWindow = 8; // passes the fit looks back on

    void record(double units, double seconds);
    // (a, b) by least squares over the window; with too little spread in the shares to tell them
    // apart, a = 0 and b = the mean seconds per unit; (0, 0) before any record.
    std::pair<double, double> model() const;

    // `total` units shared so that a_r + b_r c_r is equal for all r (summing to total), with at
    // least a tenth of an equal share each, so that no process starves and each goes on being
    // measured; equal shares where any b_r is not positive. The same inputs give the same split
    // anywhere.
    static std::vector<uint32_t> split(uint32_t total, const std::vector<double>& a, const std::vector<double>& b);

private:
    std::deque<std::pair<double, double>> samples_;
};

// Every process's model of itself, shared (device/cluster.h), and the split they give: the same
// on every process. `mine` is this process's.
std::vector<uint32_t> ranks_split(uint32_t total, const WorkBalance& mine);

} // namespace clppm

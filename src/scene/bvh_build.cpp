// Binned-SAH build of the BVH_WIDTH-wide BVH (Wald 2007, "On fast construction of SAH-based bounding volume
// hierarchies": centroid binning, sweep over bin boundaries). Each node is filled by repeatedly
// splitting its largest-area slot in two, as Embree builds its wide BVHs (Wald et al. 2014, Sec. 4.2).
#include "scene/bvh_build.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace clppm {

namespace {

constexpr int kBins = 32;
constexpr int kWidth = BVH_WIDTH; // children per node
constexpr float kInf = std::numeric_limits<float>::infinity();

struct Box {
    float lo[3] = {kInf, kInf, kInf};
    float hi[3] = {-kInf, -kInf, -kInf};

    void grow(const Box& b) {
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], b.lo[k]);
            hi[k] = std::max(hi[k], b.hi[k]);
        }
    }
    void grow(const float p[3]) {
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], p[k]);
            hi[k] = std::max(hi[k], p[k]);
        }
    }
    bool empty() const { return !(lo[0] <= hi[0]); }
    // Half the surface area, in double so that 1e4-scaled scenes times many triangles stay exact enough.
    double half_area() const {
        if (empty()) return 0;
        double dx = double(hi[0]) - lo[0], dy = double(hi[1]) - lo[1], dz = double(hi[2]) - lo[2];
        return dx * dy + dy * dz + dz * dx;
    }
};

// A contiguous run [begin, end) of the triangle index array, with the bounds of its triangles
// (box) and of their centroids (cbox, what the bins divide).
struct Range {
    uint32_t begin = 0, end = 0;
    Box box, cbox;
    uint32_t size() const { return end - begin; }
};

dev::BvhNode empty_node() {
    dev::BvhNode n;
    for (int i = 0; i < kWidth; ++i) {
        n.bmin_x[i] = n.bmin_y[i] = n.bmin_z[i] = kInf;
        n.bmax_x[i] = n.bmax_y[i] = n.bmax_z[i] = -kInf;
        n.child[i] = -1; // ~0: a leaf of count 0 (empty slot)
        n.count[i] = 0;
    }
    return n;
}

// A leaf's triangles are tested BVH_TRI_BLOCK at a time (bvh_leaf_blocks): its cost in the SAH is
// its number of blocks, as in Embree's builders.
double leaf_blocks(uint32_t n) { return double((n + BVH_TRI_BLOCK - 1) / BVH_TRI_BLOCK); }

class Builder {
public:
    Builder(const std::vector<Vec3>& positions, const BvhBuildOptions& options) : opt_(options) {
        const size_t n = positions.size() / 3;
        prim_box_.resize(n);
        centroid_.resize(n);
        idx_.resize(n);
        for (size_t i = 0; i < n; ++i) {
            Box b;
            for (int k = 0; k < 3; ++k) {
                const Vec3& p = positions[3 * i + k];
                const float v[3] = {p.x, p.y, p.z};
                b.grow(v);
            }
            prim_box_[i] = b;
            // Centroid of the box, not of the triangle: long thin triangles bin by their extent.
            for (int k = 0; k < 3; ++k) centroid_[i][k] = 0.5f * b.lo[k] + 0.5f * b.hi[k];
            idx_[i] = uint32_t(i);
        }
    }

    void build(BvhBuildResult& out) {
        nodes_.reserve(std::max<size_t>(1, idx_.size() / 2));
        if (idx_.empty()) {
            nodes_.push_back(empty_node());
            max_depth_ = 1;
        } else {
            build_inner(make_range(0, uint32_t(idx_.size())), 1);
        }
        out.nodes = std::move(nodes_);
        out.tri_order = std::move(idx_);
        out.leaf_count = leaf_count_;
        out.max_depth = max_depth_;
    }

private:
    Range make_range(uint32_t begin, uint32_t end) const {
        Range r;
        r.begin = begin;
        r.end = end;
        for (uint32_t i = begin; i < end; ++i) {
            r.box.grow(prim_box_[idx_[i]]);
            r.cbox.grow(centroid_[idx_[i]].data());
        }
        return r;
    }

    // Inner-node levels a median build needs to bring `count` triangles down to leaves.
    unsigned median_levels(uint32_t count) const {
        unsigned levels = 1;
        for (double cap = double(kWidth) * opt_.max_leaf; cap < count; cap *= kWidth) ++levels;
        return levels;
    }

    // Object-median split along the widest centroid axis: always succeeds for >= 2 triangles, even
    // when every centroid coincides (then the order is arbitrary but the halves are balanced).
    void split_median(const Range& r, Range& left, Range& right) {
        int axis = 0;
        float ext = -1;
        for (int k = 0; k < 3; ++k)
            if (r.cbox.hi[k] - r.cbox.lo[k] > ext) ext = r.cbox.hi[k] - r.cbox.lo[k], axis = k;
        const uint32_t mid = r.begin + r.size() / 2;
        std::nth_element(idx_.begin() + r.begin, idx_.begin() + mid, idx_.begin() + r.end,
                         [&](uint32_t a, uint32_t b) { return centroid_[a][axis] < centroid_[b][axis]; });
        left = make_range(r.begin, mid);
        right = make_range(mid, r.end);
    }

    // Binned SAH split. Returns false when the centroids have no extent on any axis. *cost is the
    // SAH cost of the two halves relative to the parent, (A_L B_L + A_R B_R) / A with B the blocks
    // of BVH_TRI_BLOCK triangles a side would need as one leaf.
    bool split_sah(const Range& r, Range& left, Range& right, double* cost) {
        struct Bin {
            Box box;
            uint32_t count = 0;
        };
        Bin bins[3][kBins];
        float scale[3];
        bool usable[3];
        for (int k = 0; k < 3; ++k) {
            const float ext = r.cbox.hi[k] - r.cbox.lo[k];
            usable[k] = ext > 0 && std::isfinite(ext);
            // Slightly under kBins / ext so that the maximum centroid lands in the last bin.
            scale[k] = usable[k] ? float(kBins) * (1.0f - 1e-6f) / ext : 0.0f;
        }
        auto bin_of = [&](uint32_t prim, int k) {
            int b = int((centroid_[prim][k] - r.cbox.lo[k]) * scale[k]);
            return std::min(std::max(b, 0), kBins - 1);
        };
        for (uint32_t i = r.begin; i < r.end; ++i) {
            const uint32_t p = idx_[i];
            for (int k = 0; k < 3; ++k) {
                if (!usable[k]) continue;
                Bin& b = bins[k][bin_of(p, k)];
                b.box.grow(prim_box_[p]);
                ++b.count;
            }
        }
        double best = std::numeric_limits<double>::infinity();
        int best_axis = -1, best_split = 0;
        for (int k = 0; k < 3; ++k) {
            if (!usable[k]) continue;
            // Sweep from the right, then from the left: cost of splitting after bin s.
            double right_cost[kBins];
            Box acc;
            uint32_t n = 0;
            for (int s = kBins - 1; s > 0; --s) {
                acc.grow(bins[k][s].box);
                n += bins[k][s].count;
                right_cost[s] = acc.half_area() * blocks(n);
            }
            acc = Box();
            n = 0;
            for (int s = 0; s < kBins - 1; ++s) {
                acc.grow(bins[k][s].box);
                n += bins[k][s].count;
                if (n == 0 || n == r.size()) continue;
                const double c = acc.half_area() * blocks(n) + right_cost[s + 1];
                if (c < best) best = c, best_axis = k, best_split = s;
            }
        }
        if (best_axis < 0) return false;
        auto mid_it = std::partition(idx_.begin() + r.begin, idx_.begin() + r.end,
                                     [&](uint32_t p) { return bin_of(p, best_axis) <= best_split; });
        const uint32_t mid = uint32_t(mid_it - idx_.begin());
        left = make_range(r.begin, mid);
        right = make_range(mid, r.end);
        const double area = r.box.half_area();
        *cost = area > 0 ? best / area : blocks(r.size());
        return true;
    }

    static double blocks(uint32_t n) { return leaf_blocks(n); }

    // Splits r by SAH (median when forced or when SAH finds no split); returns the relative cost.
    double split(const Range& r, bool median, Range& left, Range& right) {
        double cost = blocks(r.size());
        if (median || !split_sah(r, left, right, &cost)) split_median(r, left, right);
        return cost;
    }

    // A range becomes a leaf when it is small enough and the SAH does not favour a split: the
    // leaf costs one test per block, the split its expected tests plus one more slot to visit.
    bool leaf_is_better(const Range& r, double split_cost) const {
        return r.size() <= opt_.max_leaf && blocks(r.size()) <= split_cost + opt_.node_cost;
    }

    int32_t build_inner(const Range& r, unsigned depth) {
        const uint32_t me = uint32_t(nodes_.size());
        nodes_.push_back(empty_node());
        max_depth_ = std::max(max_depth_, depth);
        // SAH only while a median build from here would still fit under BVH_MAX_DEPTH.
        const bool median = !opt_.sah || depth + median_levels(r.size()) > BVH_MAX_DEPTH;

        Range kid[kWidth];
        bool leaf[kWidth] = {};
        int n = 1;
        kid[0] = r;
        // Open the slot with the largest surface area (largest count for median builds).
        while (n < kWidth) {
            int pick = -1;
            double best = -1;
            for (int i = 0; i < n; ++i) {
                if (leaf[i] || kid[i].size() <= 1) continue;
                const double key = median ? double(kid[i].size()) : kid[i].box.half_area();
                if (key > best) best = key, pick = i;
            }
            if (pick < 0) break;
            Range left, right;
            const Range whole = kid[pick];
            const double cost = split(whole, median, left, right);
            if (median ? whole.size() <= opt_.max_leaf : leaf_is_better(whole, cost)) {
                leaf[pick] = true; // the split reordered the range; harmless, it stays one leaf
                continue;
            }
            kid[pick] = left;
            kid[n++] = right;
        }
        // Slots not yet decided: small ones may still prefer a leaf, the rest get a node.
        int32_t child[kWidth];
        for (int i = 0; i < n; ++i) {
            if (!leaf[i] && kid[i].size() <= opt_.max_leaf) {
                if (kid[i].size() <= 1 || median) {
                    leaf[i] = true;
                } else {
                    Range left, right;
                    leaf[i] = leaf_is_better(kid[i], split(kid[i], false, left, right));
                }
            }
            if (leaf[i]) {
                child[i] = ~int32_t(kid[i].begin);
                ++leaf_count_;
            } else {
                child[i] = build_inner(kid[i], depth + 1);
            }
        }
        dev::BvhNode& node = nodes_[me]; // after the recursion: nodes_ may have grown
        for (int i = 0; i < n; ++i) {
            node.bmin_x[i] = kid[i].box.lo[0];
            node.bmin_y[i] = kid[i].box.lo[1];
            node.bmin_z[i] = kid[i].box.lo[2];
            node.bmax_x[i] = kid[i].box.hi[0];
            node.bmax_y[i] = kid[i].box.hi[1];
            node.bmax_z[i] = kid[i].box.hi[2];
            node.child[i] = child[i];
            node.count[i] = leaf[i] ? kid[i].size() : 0;
        }
        return int32_t(me);
    }

    BvhBuildOptions opt_;
    std::vector<Box> prim_box_;
    std::vector<std::array<float, 3>> centroid_;
    std::vector<uint32_t> idx_;
    std::vector<dev::BvhNode> nodes_;
    size_t leaf_count_ = 0;
    unsigned max_depth_ = 0;
};

// An edge e with fl(a + e) == b when one exists within a few ulps of fl(b - a), else the one
// that comes closest.
float exact_edge(float a, float b) {
    const float e = b - a;
    if (a + e == b) return e;
    float best = e, up = e, down = e;
    auto err = [&](float x) { return std::fabs(double(a + x) - double(b)); };
    for (int i = 0; i < 4; ++i) {
        up = std::nextafter(up, kInf);
        down = std::nextafter(down, -kInf);
        for (float x : {up, down}) {
            if (a + x == b) return x;
            if (err(x) < err(best)) best = x;
        }
    }
    return best;
}

double sah_cost_of(const std::vector<dev::BvhNode>& nodes, int32_t index, double node_cost) {
    const dev::BvhNode& n = nodes[size_t(index)];
    double cost = 0;
    for (int i = 0; i < kWidth; ++i) {
        if (n.child[i] < 0 && n.count[i] == 0) continue;
        const double dx = double(n.bmax_x[i]) - n.bmin_x[i], dy = double(n.bmax_y[i]) - n.bmin_y[i],
                     dz = double(n.bmax_z[i]) - n.bmin_z[i];
        const double area = dx * dy + dy * dz + dz * dx;
        cost += n.child[i] >= 0 ? area * node_cost + sah_cost_of(nodes, n.child[i], node_cost)
                                : area * leaf_blocks(n.count[i]);
    }
    return cost; // sum of area-weighted costs; normalised by the caller
}

} // namespace

BvhBuildResult build_bvh(const std::vector<Vec3>& positions) { return build_bvh(positions, BvhBuildOptions()); }

BvhBuildResult build_bvh(const std::vector<Vec3>& positions, const BvhBuildOptions& options) {
    const auto t0 = std::chrono::steady_clock::now();
    BvhBuildResult result;
    Builder builder(positions, options);
    builder.build(result);
    result.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return result;
}

std::vector<std::array<float, 4>> bvh_triangle_data(const std::vector<Vec3>& p) {
    std::vector<std::array<float, 4>> out(p.size());
    for (size_t t = 0; t + 2 < p.size(); t += 3) {
        const Vec3 &a = p[t], &b = p[t + 1], &c = p[t + 2];
        out[t + 1] = {exact_edge(a.x, b.x), exact_edge(a.y, b.y), exact_edge(a.z, b.z), 0.0f};
        out[t + 2] = {exact_edge(a.x, c.x), exact_edge(a.y, c.y), exact_edge(a.z, c.z), 0.0f};
        // v0.w: the largest error of a reconstructed vertex coordinate (0 almost always); the
        // kernel widens this triangle's edges by it. The residuals are exact (Sterbenz).
        float delta = 0;
        for (int k = 1; k <= 2; ++k) {
            const Vec3& v = p[t + k];
            const auto& e = out[t + k];
            delta = std::max(
                {delta, std::fabs(v.x - (a.x + e[0])), std::fabs(v.y - (a.y + e[1])), std::fabs(v.z - (a.z + e[2]))});
        }
        out[t] = {a.x, a.y, a.z, delta};
    }
    return out;
}

std::vector<dev::BvhTriBlock> bvh_leaf_blocks(std::vector<dev::BvhNode>& nodes, const std::vector<Vec3>& p) {
    std::vector<dev::BvhTriBlock> blocks;
    blocks.reserve(p.size() / 3 / BVH_TRI_BLOCK + nodes.size());
    for (dev::BvhNode& n : nodes) {
        for (int i = 0; i < kWidth; ++i) {
            if (n.child[i] >= 0 || n.count[i] == 0) continue;
            const uint32_t first = uint32_t(~n.child[i]), count = n.count[i];
            n.child[i] = ~int32_t(blocks.size());
            for (uint32_t b = 0; b < count; b += BVH_TRI_BLOCK) {
                dev::BvhTriBlock blk;
                for (uint32_t lane = 0; lane < BVH_TRI_BLOCK; ++lane) {
                    const uint32_t t = first + std::min(b + lane, count - 1); // unused lanes repeat the last
                    for (int j = 0; j < 3; ++j) {
                        const Vec3& v = p[3 * size_t(t) + size_t(j)];
                        blk.v[3 * j + 0][lane] = v.x;
                        blk.v[3 * j + 1][lane] = v.y;
                        blk.v[3 * j + 2][lane] = v.z;
                    }
                    blk.prim[lane] = t;
                }
                blocks.push_back(blk);
            }
        }
    }
    return blocks;
}

double bvh_sah_cost(const std::vector<dev::BvhNode>& nodes, double node_cost) {
    if (nodes.empty()) return 0;
    Box root;
    const dev::BvhNode& n = nodes[0];
    for (int i = 0; i < kWidth; ++i) {
        const float lo[3] = {n.bmin_x[i], n.bmin_y[i], n.bmin_z[i]}, hi[3] = {n.bmax_x[i], n.bmax_y[i], n.bmax_z[i]};
        if (lo[0] <= hi[0]) root.grow(lo), root.grow(hi);
    }
    const double area = root.half_area();
    if (area <= 0) return node_cost;
    return node_cost + sah_cost_of(nodes, 0, node_cost) / area;
}

} // namespace clppm

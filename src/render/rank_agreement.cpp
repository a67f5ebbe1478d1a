#include "render/rank_agreement.h"

#include <algorithm>

#include "device/cluster.h"
#include "util/error.h"

namespace clppm {

void require_ranks_agree(const Json& what) {
    Cluster& cl = cluster();
    if (!cl.distributed()) return;
    // Every rank's text, rank after rank: the collectives carry doubles, a byte each.
    const std::string mine = what.dump();
    const std::vector<double> sizes = cl.all_values(double(mine.size()));
    const size_t longest = size_t(*std::max_element(sizes.begin(), sizes.end()));
    std::vector<double> bytes(longest, 0.0);
    for (size_t i = 0; i < mine.size(); ++i) bytes[i] = double(static_cast<unsigned char>(mine[i]));
    const std::vector<double> all = cl.all_values(bytes);
    auto text_of = [&](int rank) {
        std::string t;
        for (size_t i = 0; i < size_t(sizes[size_t(rank)]); ++i) t += char(int(all[size_t(rank) * longest + i]));
        return t;
    };
    const Json first = Json::parse(text_of(0));
    std::string diff;
    for (int r = 1; r < cl.size(); ++r) {
        const Json other = Json::parse(text_of(r));
        for (auto it = first.begin(); it != first.end(); ++it) {
            const Json theirs = other.contains(it.key()) ? other[it.key()] : Json();
            if (theirs != it.value() && diff.size() < 300)
                diff += (diff.empty() ? "" : "; ") + it.key() + " " + it.value().dump() + " on rank 0, " +
                        theirs.dump() + " on rank " + std::to_string(r);
        }
    }
    if (!diff.empty())
        throw ErrorOnEveryRank("the " + std::to_string(cl.size()) +
                               " MPI processes were not started alike (each must render the same thing): " + diff);
}

} // namespace clppm

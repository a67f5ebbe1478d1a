#include "io/stats_json.h"

#include "io/atomic_file.h"

namespace clppm {

std::string to_json_text(const Json& stats) {
    // error_handler_t::replace: invalid UTF-8 in a user-supplied string (a scene path) must not
    // turn the end of a long render into an exception.
    return stats.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

void write_stats_json(const std::string& path, const Json& stats) { write_file_atomic(path, to_json_text(stats)); }

} // namespace clppm

// --stats-json: render statistics as a JSON object, for scripts and benchmarks. The document is
// an nlohmann::ordered_json so keys keep the order they were added in (readable diffs), and it is
// written atomically like the images.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

namespace clppm {

using Json = nlohmann::ordered_json;

// Pretty-printed (2-space indent) with a trailing newline. JSON has no NaN or Inf: such numbers
// are written as null, so a broken statistic shows up as null instead of making the file invalid.
std::string to_json_text(const Json& stats);

// Writes to_json_text(stats) to `path` via write_file_atomic; throws clppm::Error naming the path.
void write_stats_json(const std::string& path, const Json& stats);

} // namespace clppm

// stats_json: valid JSON in insertion order, non-finite numbers as null, written atomically.
#include "io/stats_json.h"

#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "test_util.h"
#include "util/error.h"

namespace clppm {
namespace {

TEST(StatsJson, KeepsKeyOrderAndWritesNullForNonFinite) {
    Json stats;
    stats["passes"] = 64;
    stats["alpha"] = 0.7;
    stats["mean"] = std::nan("");
    stats["device"] = "pthread-cpu";
    stats["timings"] = {{"trace_ms", 1.5}, {"gather_ms", 2.0}};
    std::string text = to_json_text(stats);
    EXPECT_LT(text.find("passes"), text.find("alpha"));
    EXPECT_LT(text.find("alpha"), text.find("mean"));
    EXPECT_NE(text.find("\"mean\": null"), std::string::npos) << text;
    EXPECT_EQ(text.back(), '\n');
    Json back = Json::parse(text);
    EXPECT_EQ(back["passes"], 64);
    EXPECT_EQ(back["timings"]["gather_ms"], 2.0);
}

TEST(StatsJson, WritesFileAndNamesPathOnError) {
    std::string dir = test::make_temp_dir("stats_json");
    write_stats_json(dir + "/s.json", Json{{"ok", true}});
    std::ifstream in(dir + "/s.json");
    EXPECT_EQ(Json::parse(in)["ok"], true);
    try {
        write_stats_json(dir + "/missing/s.json", Json::object());
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(dir + "/missing/s.json"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace clppm

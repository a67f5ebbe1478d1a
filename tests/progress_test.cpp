// progress: the pure line formatting, and how often the reporter draws on a terminal and in logs.
#include "render/progress.h"

#include <algorithm>
#include <cstdio>

#include <gtest/gtest.h>

namespace clppm {
namespace {

ProgressInfo info(uint64_t pass, uint64_t pass_limit, double time_limit, double elapsed) {
    ProgressInfo p;
    p.pass = pass;
    p.pass_limit = pass_limit;
    p.time_limit = time_limit;
    p.photons = pass * 200000;
    p.radius = 0.0123;
    p.elapsed_s = elapsed;
    return p;
}

TEST(Progress, FormatCount) {
    EXPECT_EQ(format_count(0), "0");
    EXPECT_EQ(format_count(999), "999");
    EXPECT_EQ(format_count(1000), "1.00k");
    EXPECT_EQ(format_count(12345), "12.3k");
    EXPECT_EQ(format_count(999499), "999k");
    EXPECT_EQ(format_count(999999), "1.00M");
    EXPECT_EQ(format_count(5400000), "5.40M");
    EXPECT_EQ(format_count(2000000000), "2.00G");
    EXPECT_EQ(format_count(UINT64_MAX), "18.4E");
}

TEST(Progress, FormatDuration) {
    EXPECT_EQ(format_duration(0), "0s");
    EXPECT_EQ(format_duration(42.4), "42s");
    EXPECT_EQ(format_duration(59.6), "1m00s");
    EXPECT_EQ(format_duration(185), "3m05s");
    EXPECT_EQ(format_duration(3725), "1h02m");
    EXPECT_EQ(format_duration(-5), "0s");
}

TEST(Progress, LineWithPassLimit) {
    EXPECT_EQ(format_progress_line(info(16, 64, 0, 8.0), true),
              "[#####---------------]  25% pass 16/64  3.20M photons  r 0.0123  2.00 pass/s  8s  ETA 24s");
    EXPECT_EQ(format_progress_line(info(16, 64, 0, 8.0), false),
              " 25% pass 16/64  3.20M photons  r 0.0123  2.00 pass/s  8s  ETA 24s");
}

TEST(Progress, LineWithoutLimitHasNoBarOrEta) {
    EXPECT_EQ(format_progress_line(info(500, 0, 0, 100.0), true),
              "pass 500  100M photons  r 0.0123  5.00 pass/s  1m40s");
}

TEST(Progress, TimeLimitAndTheNearerLimitWins) {
    // 10 of 1000 passes took 10 s, but the 30 s limit comes first.
    ProgressInfo p = info(10, 1000, 30.0, 10.0);
    EXPECT_NEAR(progress_fraction(p), 1.0 / 3.0, 1e-12);
    EXPECT_DOUBLE_EQ(progress_eta(p), 20.0);
    EXPECT_EQ(format_progress_line(p, true),
              "[######--------------]  33% pass 10/1000  2.00M photons  r 0.0123  1.00 pass/s  10s  ETA 20s");
    // Time only: the pass count has no denominator.
    EXPECT_EQ(format_progress_line(info(3, 0, 60.0, 15.0), false),
              " 25% pass 3  600k photons  r 0.0123  0.20 pass/s  15s  ETA 45s");
}

TEST(Progress, StartAndFinish) {
    ProgressInfo start = info(0, 64, 0, 0.0);
    EXPECT_LT(progress_eta(start), 0);
    EXPECT_EQ(format_progress_line(start, true),
              "[--------------------]   0% pass 0/64  0 photons  r 0.0123  - pass/s  0s  ETA ?");
    ProgressInfo done = info(64, 64, 0, 32.0);
    done.finished = true;
    EXPECT_EQ(format_progress_line(done, true),
              "[####################] 100% pass 64/64  12.8M photons  r 0.0123  2.00 pass/s  32s  done");
    EXPECT_EQ(progress_fraction(info(5, 0, 0, 1.0)), -1.0);
    EXPECT_EQ(progress_fraction(info(70, 64, 0, 1.0)), 1.0); // clamped
}

std::string captured(std::FILE* f) {
    std::fflush(f);
    std::rewind(f);
    std::string s;
    int c;
    while ((c = std::fgetc(f)) != EOF) s += static_cast<char>(c);
    std::fseek(f, 0, SEEK_END); // C requires a seek between reading and writing again
    return s;
}

size_t count_of(const std::string& s, char c) { return static_cast<size_t>(std::count(s.begin(), s.end(), c)); }

TEST(Progress, TerminalRedrawsAtMostTenTimesASecond) {
    std::FILE* f = std::tmpfile();
    {
        Progress progress(f, true, false, 1000, 0);
        for (int pass = 1; pass <= 1000; ++pass) progress.update(pass, pass * 10ull, 0.5, pass * 0.001);
        progress.finish(1000, 10000, 0.5, 1.0);
    }
    std::string out = captured(f);
    std::fclose(f);
    EXPECT_LE(count_of(out, '\r'), 12u); // 1 s of updates: ~10 redraws plus the final line
    EXPECT_GE(count_of(out, '\r'), 9u);
    EXPECT_EQ(count_of(out, '\n'), 1u);
    EXPECT_NE(out.find("done"), std::string::npos);
}

TEST(Progress, PlainLinesAreSparse) {
    std::FILE* f = std::tmpfile();
    {
        Progress progress(f, false, false, 0, 20.0);
        for (int pass = 1; pass <= 200; ++pass) progress.update(pass, pass * 10ull, 0.5, pass * 0.1);
        progress.finish(200, 2000, 0.5, 20.0);
    }
    std::string out = captured(f);
    std::fclose(f);
    EXPECT_EQ(out.find('\r'), std::string::npos);
    EXPECT_EQ(out.find('['), std::string::npos); // no bar in logs
    EXPECT_LE(count_of(out, '\n'), 6u);          // 20 s at one line per 5 s, plus the final one
    EXPECT_GE(count_of(out, '\n'), 4u);
}

TEST(Progress, QuietPrintsNothingAndAbortEndsTheLine) {
    std::FILE* f = std::tmpfile();
    {
        Progress quiet(f, true, true, 10, 0);
        quiet.update(1, 1, 1, 1);
        quiet.finish(2, 2, 1, 2);
    }
    EXPECT_EQ(captured(f), "");
    {
        Progress aborted(f, true, false, 10, 0);
        aborted.update(1, 1, 1, 1); // no finish(): the destructor ends the line
    }
    std::string out = captured(f);
    std::fclose(f);
    EXPECT_EQ(out.front(), '\r');
    EXPECT_EQ(out.back(), '\n');
}

// The first pass holds the kernels' build and PoCL's first-launch compilation: the rate and the
// ETA come from the passes after it (the issue saw "ETA 10m59s" at pass 1 of 200 for a 50 s run).
TEST(Progress, EtaAndRateExcludeTheFirstPass) {
    ProgressInfo p = info(1, 200, 0, 10.0);
    p.steady_pass0 = 1, p.steady_t0 = 10.0;
    EXPECT_LT(progress_eta(p), 0);
    EXPECT_EQ(format_progress_line(p, false), "  0% pass 1/200  200k photons  r 0.0123  - pass/s  10s  ETA ?");
    p = info(5, 200, 0, 11.0); // four passes in the second after it
    p.steady_pass0 = 1, p.steady_t0 = 10.0;
    EXPECT_DOUBLE_EQ(progress_rate(p), 4.0);
    EXPECT_DOUBLE_EQ(progress_eta(p), 195.0 / 4.0);
    EXPECT_EQ(format_progress_line(p, false), "  2% pass 5/200  1.00M photons  r 0.0123  4.00 pass/s  11s  ETA 49s");
    // The reporter takes its first update as that origin.
    std::FILE* f = std::tmpfile();
    {
        Progress progress(f, false, false, 200, 0);
        progress.update(1, 1, 0.5, 10.0);
        progress.update(5, 5, 0.5, 11.0);
        progress.update(21, 21, 0.5, 15.0); // 20 passes in 5 s after the first: 4 pass/s
    }
    std::string out = captured(f);
    std::fclose(f);
    EXPECT_NE(out.find("pass 1/200  1 photons  r 0.5  - pass/s  10s  ETA ?\n"), std::string::npos) << out;
    EXPECT_NE(out.find("pass 21/200  21 photons  r 0.5  4.00 pass/s  15s  ETA 45s\n"), std::string::npos) << out;
}

TEST(Progress, ResumedRendersSayWhere) {
    ProgressInfo p = info(5, 10, 0, 2.0);
    p.resumed_at = 4;
    EXPECT_EQ(format_progress_line(p, false),
              " 50% pass 5/10 (resumed at 4)  1.00M photons  r 0.0123  0.50 pass/s  2s  ETA 10s");
    // A checkpoint already past --passes (a total) renders nothing, and says so plainly.
    p = info(4, 2, 0, 0.0);
    p.resumed_at = 4;
    p.finished = true;
    EXPECT_EQ(format_progress_line(p, false),
              "100% pass 4/4 (resumed at 4)  800k photons  r 0.0123  - pass/s  0s  done");
}

// In a log, the pass that reaches the limit is printed once, by the final line.
TEST(Progress, PlainLogPrintsTheLastPassOnce) {
    for (bool by_time : {false, true}) {
        std::FILE* f = std::tmpfile();
        {
            Progress progress(f, false, false, by_time ? 0 : 3, by_time ? 18.0 : 0);
            for (int pass = 1; pass <= 3; ++pass) progress.update(pass, pass, 0.5, 6.0 * pass);
            progress.finish(3, 3, 0.5, 18.0);
        }
        std::string out = captured(f);
        std::fclose(f);
        EXPECT_EQ(count_of(out, '\n'), 3u) << out;
        size_t first = out.find("pass 3");
        ASSERT_NE(first, std::string::npos) << out;
        EXPECT_EQ(out.find("pass 3", first + 1), std::string::npos) << out;
        EXPECT_NE(out.find("done"), std::string::npos) << out;
    }
}

} // namespace
} // namespace clppm

// Render progress on stderr. On a terminal: one line redrawn in place (at most ~10 times a
// second) with a bar when a pass or time limit is known. Otherwise (a log, CI): plain lines, at
// most one every few seconds, so logs stay short. --quiet prints nothing.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>

namespace clppm {

struct ProgressInfo {
    uint64_t pass = 0;       // passes completed
    uint64_t pass_limit = 0; // 0 = none
    double time_limit = 0.0; // seconds; 0 = none
    uint64_t photons = 0;    // photons traced so far
    double radius = 0.0;     // current gather radius (whatever the caller reports)
    double elapsed_s = 0.0;
    bool finished = false;     // the final line: "done" instead of an ETA
    double error = -1.0;       // estimated relative error (--target-error, --error-output); < 0 = none
    double target_error = 0.0; // 0 = none
    double error_eta_s = -1.0; // seconds until error <= target_error; < 0 = unknown
    uint64_t resumed_at = 0;   // passes the checkpoint held ("pass 5/10 (resumed at 4)"); 0 = fresh
    // The steady rate's origin: the pass count and elapsed time at the end of this run's first
    // pass, whose time holds the kernels' build and first-launch compilation. With it, the rate and
    // the pass limit's ETA come from the passes after it alone (the ETA is unknown until a second
    // pass is done); without it (steady_t0 < 0), from all passes.
    uint64_t steady_pass0 = 0;
    double steady_t0 = -1.0;
};

// One progress line without any terminal control characters, e.g.
// "[#########-----------]  45% pass 29/64  5.80M photons  r 0.0123  3.10 pass/s  9s  ETA 11s",
// followed by "  err 0.081" or, with a target, "  err 0.081/0.05 in 40s" when an error is known.
// `with_bar` adds the bar (only drawn when a limit is known).
std::string format_progress_line(const ProgressInfo& info, bool with_bar);

// Completed fraction in [0, 1] of whichever limit is closer; negative when there is no limit.
double progress_fraction(const ProgressInfo& info);

// Seconds left until the nearer limit; negative when unknown (no limit, or no steady pass yet).
double progress_eta(const ProgressInfo& info);

// Passes per second: after steady_pass0 when steady_t0 >= 0, else over the whole run; negative
// when unknown.
double progress_rate(const ProgressInfo& info);

// 950 -> "950", 12345 -> "12.3k", 5400000 -> "5.40M", 2e9 -> "2.00G".
std::string format_count(uint64_t n);

// 42.4 -> "42s", 185 -> "3m05s", 3725 -> "1h02m".
std::string format_duration(double seconds);

class Progress {
public:
    // Reports to stderr, redrawing in place if stderr is a terminal.
    Progress(bool quiet, uint64_t pass_limit, double time_limit);
    // Reports to `out`, as a terminal or not; for tests.
    Progress(std::FILE* out, bool terminal, bool quiet, uint64_t pass_limit, double time_limit);
    // Ends a half-drawn terminal line, so that an error printed after an aborted render starts on
    // a line of its own.
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    // Call after each pass; draws only if enough time has passed since the last line.
    void update(uint64_t pass, uint64_t photons, double radius, double elapsed_s);
    // The estimated error (and the target and the time to reach it) shown from now on.
    void set_error(double error, double target, double eta_s);
    // This run continues a checkpoint of `passes` passes (shown on every line).
    void set_resumed(uint64_t passes);
    // Draws the final line unconditionally (and ends it on a terminal).
    void finish(uint64_t pass, uint64_t photons, double radius, double elapsed_s);
    // What the next line would show (the live view's progress).
    ProgressInfo snapshot(uint64_t pass, uint64_t photons, double radius, double elapsed_s) const {
        return info(pass, photons, radius, elapsed_s);
    }

private:
    ProgressInfo info(uint64_t pass, uint64_t photons, double radius, double elapsed_s) const;
    void draw(const ProgressInfo& info);

    std::FILE* out_;
    bool terminal_;
    bool quiet_;
    uint64_t pass_limit_;
    double time_limit_;
    double error_ = -1.0, target_error_ = 0.0, error_eta_s_ = -1.0;
    uint64_t resumed_at_ = 0;
    uint64_t steady_pass0_ = 0; // pass and time of the first update (steady_t0)
    double steady_t0_ = -1.0;
    bool drawn_ = false; // a line has been drawn
    double last_draw_s_ = 0.0;
    size_t last_length_ = 0; // of the terminal line, to blank out leftovers of a longer one
    bool line_open_ = false; // a terminal line without its newline yet
};

} // namespace clppm

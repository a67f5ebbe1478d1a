#include "render/progress.h"

#include <algorithm>
#include <cmath>
#include <sys/ioctl.h>
#include <unistd.h>

namespace clppm {
namespace {

constexpr double kTerminalInterval = 0.1; // s between redraws: ~10 per second
constexpr double kPlainInterval = 5.0;    // s between lines in logs
constexpr int kBarWidth = 20;

std::string printf_string(const char* format, double value) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, value);
    return buf;
}

// Three significant digits, so the width stays steady while the numbers grow.
std::string three_digits(double v) { return printf_string(v < 10 ? "%.2f" : v < 100 ? "%.1f" : "%.0f", v); }

std::string bar(double fraction) {
    int filled = static_cast<int>(fraction * kBarWidth);
    return "[" + std::string(filled, '#') + std::string(kBarWidth - filled, '-') + "]";
}

std::string pass_text(const ProgressInfo& p) {
    std::string s = "pass " + std::to_string(p.pass);
    // A checkpoint past the limit (--passes counts from the original start) renders nothing: the
    // limit shown is then what was already done, never "pass 4/2".
    if (p.pass_limit > 0) s += "/" + std::to_string(std::max(p.pass_limit, p.resumed_at));
    if (p.resumed_at > 0) s += " (resumed at " + std::to_string(p.resumed_at) + ")";
    return s;
}

std::string rate_text(const ProgressInfo& p) {
    double rate = progress_rate(p);
    return rate < 0 ? "- pass/s" : three_digits(rate) + " pass/s";
}

std::string eta_text(const ProgressInfo& p) {
    if (p.finished) return "done";
    if (p.pass_limit == 0 && p.time_limit <= 0) return "";
    double eta = progress_eta(p);
    return eta < 0 ? "ETA ?" : "ETA " + format_duration(eta);
}

std::string error_text(const ProgressInfo& p) {
    if (p.error < 0) return "";
    std::string s = "  err " + (std::isfinite(p.error) ? printf_string("%.3g", p.error) : std::string("?"));
    if (p.target_error <= 0) return s;
    s += "/" + printf_string("%.3g", p.target_error);
    if (!p.finished) s += p.error_eta_s < 0 ? " in ?" : " in " + format_duration(p.error_eta_s);
    return s;
}

// Columns of the terminal, so the line never wraps (a wrapped line defeats \r); 0 if unknown.
size_t terminal_columns(std::FILE* out) {
    struct winsize ws;
    if (::ioctl(fileno(out), TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0) return ws.ws_col;
    return 0;
}

} // namespace

double progress_fraction(const ProgressInfo& p) {
    double f = -1.0;
    if (p.pass_limit > 0) f = std::max(f, static_cast<double>(p.pass) / static_cast<double>(p.pass_limit));
    if (p.time_limit > 0) f = std::max(f, p.elapsed_s / p.time_limit);
    return f < 0 ? f : std::min(f, 1.0);
}

double progress_rate(const ProgressInfo& p) {
    const uint64_t pass0 = p.steady_t0 >= 0 ? p.steady_pass0 : p.resumed_at;
    const double t0 = p.steady_t0 >= 0 ? p.steady_t0 : 0.0;
    if (p.pass <= pass0 || !(p.elapsed_s > t0)) return -1.0;
    return static_cast<double>(p.pass - pass0) / (p.elapsed_s - t0);
}

double progress_eta(const ProgressInfo& p) {
    double eta = -1.0;
    const double rate = progress_rate(p);
    if (p.pass_limit > 0 && p.pass >= p.pass_limit) eta = 0.0;
    else if (p.pass_limit > 0 && rate > 0) eta = static_cast<double>(p.pass_limit - p.pass) / rate;
    if (p.time_limit > 0) {
        double left = std::max(0.0, p.time_limit - p.elapsed_s);
        eta = eta < 0 ? left : std::min(eta, left);
    }
    return eta;
}

std::string format_count(uint64_t n) {
    static const char* kSuffix[] = {"", "k", "M", "G", "T", "P", "E"};
    double v = static_cast<double>(n);
    int i = 0;
    while (v >= 999.5 && i < 6) { // 999.5 rounds to "1000": show it as "1.00k" instead
        v /= 1000.0;
        ++i;
    }
    if (i == 0) return std::to_string(n);
    return three_digits(v) + kSuffix[i];
}

std::string format_duration(double seconds) {
    long long t = std::llround(std::max(0.0, seconds));
    char buf[48];
    if (t < 60) std::snprintf(buf, sizeof buf, "%llds", t);
    else if (t < 3600) std::snprintf(buf, sizeof buf, "%lldm%02llds", t / 60, t % 60);
    else std::snprintf(buf, sizeof buf, "%lldh%02lldm", t / 3600, (t % 3600) / 60);
    return buf;
}

std::string format_progress_line(const ProgressInfo& p, bool with_bar) {
    std::string line;
    double fraction = progress_fraction(p);
    if (fraction >= 0) {
        if (with_bar) line += bar(fraction) + " ";
        line += printf_string("%3.0f%% ", std::floor(fraction * 100.0));
    }
    line += pass_text(p);
    line += "  " + format_count(p.photons) + " photons";
    line += "  r " + printf_string("%.3g", p.radius);
    line += "  " + rate_text(p);
    line += "  " + format_duration(p.elapsed_s);
    std::string eta = eta_text(p);
    if (!eta.empty()) line += "  " + eta;
    line += error_text(p);
    return line;
}

Progress::Progress(bool quiet, uint64_t pass_limit, double time_limit)
    : Progress(stderr, ::isatty(fileno(stderr)) != 0, quiet, pass_limit, time_limit) {}

Progress::Progress(std::FILE* out, bool terminal, bool quiet, uint64_t pass_limit, double time_limit)
    : out_(out), terminal_(terminal), quiet_(quiet), pass_limit_(pass_limit), time_limit_(time_limit) {}

Progress::~Progress() {
    if (line_open_) {
        std::fputc('\n', out_);
        std::fflush(out_);
    }
}

ProgressInfo Progress::info(uint64_t pass, uint64_t photons, double radius, double elapsed_s) const {
    return ProgressInfo{pass,   pass_limit_,   time_limit_,  photons,     radius,        elapsed_s, false,
                        error_, target_error_, error_eta_s_, resumed_at_, steady_pass0_, steady_t0_};
}

void Progress::update(uint64_t pass, uint64_t photons, double radius, double elapsed_s) {
    if (steady_t0_ < 0) { // this run's first pass: the rate is measured from here on
        steady_pass0_ = pass;
        steady_t0_ = elapsed_s;
    }
    if (quiet_) return;
    double interval = terminal_ ? kTerminalInterval : kPlainInterval;
    if (drawn_ && elapsed_s - last_draw_s_ < interval) return;
    // In a log, the pass that reaches a limit is the final line's to print (finish), not twice.
    const bool last = (pass_limit_ > 0 && pass >= pass_limit_) || (time_limit_ > 0 && elapsed_s >= time_limit_);
    if (!terminal_ && last) return;
    draw(info(pass, photons, radius, elapsed_s));
}

void Progress::set_resumed(uint64_t passes) { resumed_at_ = passes; }

void Progress::set_error(double error, double target, double eta_s) {
    error_ = error;
    target_error_ = target;
    error_eta_s_ = eta_s;
}

void Progress::finish(uint64_t pass, uint64_t photons, double radius, double elapsed_s) {
    if (quiet_) return;
    ProgressInfo p = info(pass, photons, radius, elapsed_s);
    p.finished = true;
    draw(p);
    if (line_open_) {
        std::fputc('\n', out_);
        line_open_ = false;
    }
    std::fflush(out_);
}

void Progress::draw(const ProgressInfo& p) {
    drawn_ = true;
    last_draw_s_ = p.elapsed_s;
    std::string line = format_progress_line(p, terminal_);
    if (!terminal_) {
        std::fprintf(out_, "%s\n", line.c_str());
        std::fflush(out_);
        return;
    }
    size_t columns = terminal_columns(out_);
    if (columns > 1 && line.size() > columns - 1) line.resize(columns - 1);
    size_t length = line.size();
    if (length < last_length_) line += std::string(last_length_ - length, ' ');
    last_length_ = length;
    std::fprintf(out_, "\r%s", line.c_str());
    std::fflush(out_);
    line_open_ = true;
}

} // namespace clppm

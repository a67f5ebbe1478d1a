#include "render/device_auto.h"

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "device/cache_dir.h"
#include "device/cluster.h"
#include "io/atomic_file.h"
#include "render/device_choice.h"
#include "render/render_job.h"
#include "util/error.h"
#include "util/hash.h"
#include "util/steady_seconds.h"

namespace clppm {

namespace {

std::string identity(const DeviceInfo& d) { return d.implementation() + "\t" + d.name; }

std::string describe(const DeviceInfo& d) {
    return "[" + std::to_string(d.index) + "] " + d.name + " (" + d.implementation() + ")";
}

// What the choice depends on: the candidates (their drivers' versions too), and the render as the
// options give it. A changed scene file under the same name keeps its choice: still a device that
// renders it, measured on the file as it was.
std::string cache_key(const RenderOptions& o, const std::vector<DeviceInfo>& candidates) {
    std::string k;
    for (const DeviceInfo& d : candidates) k += identity(d) + "\t" + d.driver_version + "\n";
    const RenderSettings& s = o.settings;
    k += "scene " + o.scene + "\nintegrator " + s.integrator + "\nsize " + std::to_string(s.width) + "x" +
         std::to_string(s.height) + "\nphotons " + std::to_string(s.photons) + "\ngeneric " +
         (o.generic_kernels ? "1" : "0") + "\nkernels " + o.kernel_dir + "\n";
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", fnv1a64(k));
    return hex;
}

std::string cache_file() {
    const std::string dir = cache_dir();
    return dir.empty() ? "" : dir + "/device-auto.txt";
}

// The cache: one line per key, "KEY IMPLEMENTATION<tab>DEVICE NAME".
std::map<std::string, std::string> read_cache(const std::string& path) {
    std::map<std::string, std::string> entries;
    std::ifstream f(path);
    std::string line;
    while (std::getline(f, line)) {
        const size_t space = line.find(' ');
        if (space == 16) entries[line.substr(0, space)] = line.substr(space + 1);
    }
    return entries;
}

void write_cache(const std::string& path, const std::map<std::string, std::string>& entries) {
    std::string text;
    for (const auto& [key, device] : entries) text += key + " " + device + "\n";
    try {
        make_dirs(path.substr(0, path.rfind('/')));
        write_file_atomic(path, text);
    } catch (const Error&) { // an unwritable cache costs a measurement next time, nothing more
    }
}

// One candidate renders the job for a moment: one untimed pass (the first pays for work-group
// functions built on first use), then at least kTrialPasses passes and kTrialSeconds seconds.
DeviceTrial trial(const RenderOptions& options, const DeviceInfo& device) {
    RenderOptions o = options;
    o.devices = {std::to_string(device.index)};
    o.output.clear();
    o.stats_json.clear();
    o.checkpoint.clear();
    o.error_output.clear();
    o.resume.clear();
    o.dump_kernel_source.clear();
    RenderLog quiet = RenderLog::silent();
    RenderJob job(o, quiet);
    job.run_pass();
    DeviceTrial t{device};
    const double t0 = steady_seconds();
    const uint64_t p0 = job.passes();
    do job.run_pass();
    while (job.passes() - p0 < kTrialPasses || steady_seconds() - t0 < kTrialSeconds);
    t.passes = job.passes() - p0;
    t.seconds = steady_seconds() - t0;
    return t;
}

} // namespace

bool wants_auto_device(const std::vector<std::string>& specs) {
    for (const std::string& s : specs)
        if (s == "auto") {
            if (specs.size() > 1) throw Error("--device auto: measures the devices to pick one; give it alone");
            return true;
        }
    return false;
}

std::vector<DeviceInfo> auto_candidates(const std::vector<DeviceInfo>& devices) {
    std::vector<DeviceInfo> out;
    for (const DeviceInfo& d : devices) {
        bool seen = false;
        for (const DeviceInfo& c : out) seen = seen || identity(c) == identity(d);
        if (!seen) out.push_back(d);
    }
    return out;
}

const DeviceTrial& pick_trial(const std::vector<DeviceTrial>& trials, const DeviceInfo& default_device) {
    const DeviceTrial* best = &trials.front();
    for (const DeviceTrial& t : trials)
        if (t.device.index == default_device.index) best = &t;
    const double keep = best->passes_per_second() * (1.0 + kAutoMargin);
    for (const DeviceTrial& t : trials)
        if (t.passes_per_second() > keep && t.passes_per_second() > best->passes_per_second()) best = &t;
    return *best;
}

DeviceInfo auto_device(const RenderOptions& options, const std::vector<DeviceInfo>& devices, RenderLog& log) {
    if (cluster().distributed())
        throw Error("--device auto: each of several processes would measure its own machine; name the device");
    const std::vector<DeviceInfo> candidates = auto_candidates(devices);
    const DeviceInfo fallback = choose_devices({}, devices).front(); // throws when there is no device
    if (candidates.size() == 1) {
        log.note("--device auto: " + describe(fallback) + ", the only device");
        return fallback;
    }
    const std::string path = cache_file(), key = cache_key(options, candidates);
    std::map<std::string, std::string> cache = path.empty() ? std::map<std::string, std::string>() : read_cache(path);
    if (const auto hit = cache.find(key); hit != cache.end())
        for (const DeviceInfo& d : candidates)
            if (identity(d) == hit->second) {
                log.note("--device auto: " + describe(d) + ", measured the fastest before (" + path + ")");
                return d;
            }
    std::vector<DeviceTrial> trials;
    std::string failed;
    for (const DeviceInfo& d : candidates) {
        try {
            trials.push_back(trial(options, d));
        } catch (const Error& e) { // a device that cannot render this scene is no candidate
            failed += "; " + describe(d) + " cannot render it: " + e.what();
        }
    }
    if (trials.empty()) throw Error("--device auto: no device renders this scene" + failed);
    const DeviceTrial& best = pick_trial(trials, fallback);
    std::string rates;
    for (const DeviceTrial& t : trials) {
        if (&t == &best) continue;
        char r[64];
        std::snprintf(r, sizeof r, "%.3g on ", t.passes_per_second());
        rates += std::string(rates.empty() ? "" : ", ") + r + describe(t.device);
    }
    char own[64];
    std::snprintf(own, sizeof own, "%.3g passes/s there", best.passes_per_second());
    log.note("--device auto: rendering on " + describe(best.device) + "; measured " + own + ", " + rates +
             " (the default device is kept unless another is over 10% faster)" + failed);
    if (!path.empty()) {
        cache[key] = identity(best.device);
        write_cache(path, cache);
    }
    return best.device;
}

} // namespace clppm

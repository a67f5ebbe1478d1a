#include "device/kernel_program.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "device/cache_dir.h"
#include "io/atomic_file.h"
#include "io/regular_file.h"
#include "util/embedded_files.h"
#include "util/error.h"
#include "util/hash.h"

namespace clppm {

namespace {

thread_local const std::string* t_kernel_dir = nullptr; // the innermost KernelDirScope's

bool read_file(const std::string& path, std::string* out) {
    if (!not_a_regular_file(path).empty()) return false;
    std::ifstream f(path, std::ios::binary);
    if (!f) return false;
    std::ostringstream ss;
    ss << f.rdbuf();
    *out = ss.str();
    return true;
}

std::string load_kernel_file(const std::string& name) {
    const std::string dir = kernel_dir();
    if (!dir.empty()) {
        std::string text;
        if (!read_file(dir + "/" + name, &text))
            throw Error("kernel source " + dir + "/" + name + ": cannot read (from CLPPM_KERNEL_DIR/--kernel-dir)");
        return text;
    }
    const EmbeddedFile* f = find_embedded("kernels/" + name);
    if (!f) throw Error("kernel source " + name + ": not embedded in this binary");
    return std::string(f->data, f->size);
}

void assemble(const std::string& name, std::set<std::string>& seen, std::string& out) {
    if (!seen.insert(name).second) return;
    std::istringstream in(load_kernel_file(name));
    std::string line;
    int lineno = 0;
    out += "#line 1 \"" + name + "\"\n";
    while (std::getline(in, line)) {
        ++lineno;
        size_t p = line.find_first_not_of(" \t");
        if (p != std::string::npos && line.compare(p, 8, "#include") == 0) {
            size_t q0 = line.find('"', p), q1 = q0 == std::string::npos ? q0 : line.find('"', q0 + 1);
            if (q0 != std::string::npos && q1 != std::string::npos) {
                assemble(line.substr(q0 + 1, q1 - q0 - 1), seen, out);
                out += "#line " + std::to_string(lineno + 1) + " \"" + name + "\"\n";
                continue;
            }
        }
        out += line;
        out += '\n';
    }
}

// Whether the driver keeps built programs itself, keyed as ours would be. PoCL does (in
// $POCL_CACHE_DIR, unless POCL_KERNEL_CACHE=0), and there our cache only costs: PoCL hands out a
// program's binary by compiling every kernel of it for any work-group size, 2.8 s of the 3.5 s a
// first render spent building on the two-core box, none of which a launch then reuses; a rebuild
// from source that finds PoCL's cache takes 0.03 s.
bool driver_caches_programs(const DeviceInfo& info) {
    if (info.platform_name.find("Portable Computing Language") == std::string::npos &&
        info.platform_name.find("PoCL") == std::string::npos)
        return false;
    const char* e = std::getenv("POCL_KERNEL_CACHE");
    return !(e && std::string(e) == "0");
}

std::string build_log(const cl::Program& program, const cl::Device& device) {
    try {
        return program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device);
    } catch (const cl::Error&) {
        return "(no build log)";
    }
}

} // namespace

KernelDirScope::KernelDirScope(const std::string& dir) : previous_(t_kernel_dir) {
    if (!dir.empty()) t_kernel_dir = &dir;
}

KernelDirScope::~KernelDirScope() { t_kernel_dir = previous_; }

std::string kernel_dir() {
    if (t_kernel_dir) return *t_kernel_dir;
    if (const char* e = std::getenv("CLPPM_KERNEL_DIR"); e && *e) return e;
    return "";
}

std::string assemble_kernel_source(const std::string& name) {
    std::set<std::string> seen;
    std::string out;
    assemble(name, seen, out);
    return out;
}

cl::Program build_program(const DeviceContext& dc, const std::string& entry_file, const std::string& options,
                          ProgramBuildStats* stats) {
    auto t0 = std::chrono::steady_clock::now();
    const std::string source = assemble_kernel_source(entry_file);
    const std::string full_options = "-cl-std=CL1.2 " + options;
    const cl::Device& device = dc.info.device;

    // Cache key: source, options, device and driver (LuxCore's persistent cache keys the same way).
    unsigned long long key = fnv1a64(source);
    key = fnv1a64(full_options, key);
    key = fnv1a64(dc.info.platform_name + "|" + dc.info.name + "|" + dc.info.driver_version, key);
    char keyhex[17];
    std::snprintf(keyhex, sizeof keyhex, "%016llx", key);
    const std::string dir = driver_caches_programs(dc.info) ? "" : cache_dir();
    const std::string cache_file = dir.empty() ? "" : dir + "/" + keyhex + ".bin";

    auto finish = [&](cl::Program p, bool cached) {
        if (stats) {
            stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            stats->from_cache = cached;
            stats->driver_cache = driver_caches_programs(dc.info);
            stats->options = full_options;
        }
        return p;
    };

    std::string binary;
    if (!cache_file.empty() && read_file(cache_file, &binary) && !binary.empty()) {
        try {
            cl::Program::Binaries bins{std::vector<unsigned char>(binary.begin(), binary.end())};
            cl::Program p(dc.context, {device}, bins);
            p.build({device}, full_options.c_str());
            return finish(p, true);
        } catch (const cl::Error&) {
            std::remove(cache_file.c_str()); // stale or foreign binary: rebuild from source
        }
    }

    cl::Program program(dc.context, source);
    try {
        program.build({device}, full_options.c_str());
    } catch (const cl::Error& e) {
        std::string log = build_log(program, device);
        throw Error("kernel build failed for " + entry_file + " on " + dc.info.name + " (" + full_options + "):\n" +
                    log);
    }
    if (std::getenv("CLPPM_BUILD_LOG")) std::fprintf(stderr, "%s\n", build_log(program, device).c_str());
    if (!cache_file.empty()) {
        try {
            std::vector<std::vector<unsigned char>> bins = program.getInfo<CL_PROGRAM_BINARIES>();
            if (bins.size() == 1 && !bins[0].empty()) {
                make_dirs(dir);
                try {
                    write_file_atomic(cache_file, std::string(bins[0].begin(), bins[0].end()));
                } catch (const Error&) { // an unwritable cache: the next render builds again
                }
            }
        } catch (const cl::Error&) {
            // Binaries unavailable from this driver: no caching, nothing else changes.
        }
    }
    return finish(program, false);
}

} // namespace clppm

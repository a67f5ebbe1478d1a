// clppm: progressive photon mapping on OpenCL. Dispatches to the compare command, the device
// list, or a render (cli/render_command.h).
#include <cstdio>
#include <string>

#include "cli/compare_command.h"
#include "cli/options.h"
#include "cli/render_command.h"
#include "device/cluster.h"
#include "device/device.h"
#include "util/error.h"
#include "util/version.h"

using namespace clppm;

int main(int argc, char** argv) {
    try {
        // mpirun -np N: one render on N processes (device/cluster.h); otherwise a cluster of one.
        const ClusterSession mpi(&argc, &argv);
        if (argc >= 2 && std::string(argv[1]) == "compare") return compare_command(argc - 2, argv + 2);
        const CommandLine opt = parse_options(argc, argv);
        if (opt.help) {
            std::fputs(usage().c_str(), stdout);
            return 0;
        }
        if (opt.version) {
            std::printf("%s\n", kVersion);
            return 0;
        }
        if (opt.list_devices) {
            std::fputs(describe_devices(list_devices()).c_str(), stdout);
            return 0;
        }
        return render_command(opt.render);
    } catch (const ErrorOnEveryRank& e) {
        if (cluster().rank() == 0) std::fprintf(stderr, "clppm: error: %s\n", e.what());
        return 1;
    } catch (const Error& e) {
        std::fprintf(stderr, "clppm: %serror: %s\n", cluster().prefix().c_str(), e.what());
        return 1;
    } catch (const cl::Error& e) {
        std::fprintf(stderr, "clppm: %serror: OpenCL call %s failed with code %d\n", cluster().prefix().c_str(),
                     e.what(), e.err());
        return 1;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "clppm: %serror: out of host memory\n", cluster().prefix().c_str());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "clppm: %serror: %s\n", cluster().prefix().c_str(), e.what());
        return 1;
    }
}

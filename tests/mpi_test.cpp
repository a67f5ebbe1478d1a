// One render on several processes (device/cluster.h): mpirun -np 2 and -np 3 give the image of one
// process bit for bit, for every integrator; a checkpoint written by N ranks resumes on any number;
// Ctrl-C on mpirun and a rank that dies both end the job within seconds with the last complete
// pass written and rank 0 saying why. Skipped, saying so, where clppm was built without MPI or
// mpirun is missing (scripts/install-deps.sh installs Open MPI); there, a launcher starting several
// copies is refused instead (tested here too).
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <fstream>
#include <sys/stat.h>
#include <thread>

#include <nlohmann/json.hpp>

#include "device/cluster.h"
#include "io/image_io.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

bool have_mpirun() {
    std::string out;
    return run_command("command -v mpirun", &out) == 0;
}

#define REQUIRE_MPI()                                                                                                  \
    do {                                                                                                               \
        if (!built_with_mpi()) GTEST_SKIP() << "clppm was built without MPI";                                          \
        if (!have_mpirun()) GTEST_SKIP() << "mpirun is not installed (openmpi-bin)";                                   \
    } while (0)

// mpirun as CI runs it: as root where it runs as root, more ranks than the two cores.
std::string mpirun(int ranks) {
    return "mpirun --allow-run-as-root --oversubscribe -np " + std::to_string(ranks) + " " + clppm_binary() + " ";
}

const char* kCommon = "--width 48 --height 32 --photons 12000 --quiet --no-png --seed 7";

void expect_same_pixels(const std::string& a, const std::string& b) {
    const Image x = read_exr(a), y = read_exr(b);
    ASSERT_EQ(x.rgb.size(), y.rgb.size());
    size_t differ = 0;
    for (size_t i = 0; i < x.rgb.size(); ++i) differ += x.rgb[i] != y.rgb[i];
    EXPECT_EQ(differ, 0u) << a << " and " << b << " differ in " << differ << " values";
}

} // namespace

class MpiIntegrator : public ::testing::TestWithParam<const char*> {};

// Bit for bit: one process, two ranks and three ranks; for SPPM also the error estimate, whose
// Laplacian sums travel in the same reduction.
TEST_P(MpiIntegrator, SeveralRanksGiveOneProcesssImage) {
    REQUIRE_MPI();
    const std::string integ = GetParam(), dir = make_temp_dir("mpi_" + integ);
    const std::string args = std::string(kCommon) + " --integrator " + integ + " --passes 6" +
                             (integ == "sppm" || integ == "pt" ? " --error-output " : " --stats-json ");
    std::string out;
    ASSERT_EQ(run_clppm(args + dir + "/one_err.exr -o " + dir + "/one.exr", &out), 0) << out;
    for (int ranks : {2, 3}) {
        const std::string name = dir + "/r" + std::to_string(ranks);
        ASSERT_EQ(run_command(mpirun(ranks) + args + name + "_err.exr -o " + name + ".exr --stats-json " + name +
                                  ".json 2>&1",
                              &out),
                  0)
            << out;
        expect_same_pixels(dir + "/one.exr", name + ".exr");
        if (integ == "sppm" || integ == "pt") expect_same_pixels(dir + "/one_err.exr", name + "_err.exr");
        std::ifstream js(name + ".json");
        const nlohmann::json st = nlohmann::json::parse(js);
        EXPECT_EQ(st["mpi"]["ranks"], ranks);
        EXPECT_EQ(st["mpi"]["communication_seconds"].size(), size_t(ranks));
        EXPECT_GT(st["mpi"]["bytes_per_pass"].get<double>(), 0);
        EXPECT_EQ(st["passes"], 6);
    }
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, MpiIntegrator, ::testing::Values("ppm", "sppm", "pppm", "pt", "vcm"),
                         [](const auto& p) { return std::string(p.param); });

// A checkpoint of two ranks, continued on three ranks and on one process: both equal the render
// that never stopped.
TEST(Mpi, ACheckpointResumesOnAnyNumberOfRanks) {
    REQUIRE_MPI();
    const std::string dir = make_temp_dir("mpi_resume"), args = std::string(kCommon) + " --integrator sppm";
    std::string out;
    ASSERT_EQ(run_clppm(args + " --passes 8 -o " + dir + "/straight.exr", &out), 0) << out;
    ASSERT_EQ(
        run_command(mpirun(2) + args + " --passes 4 -o " + dir + "/half.exr --checkpoint " + dir + "/ck.clppm 2>&1",
                    &out),
        0)
        << out;
    ASSERT_EQ(
        run_command(mpirun(3) + args + " --passes 8 -o " + dir + "/three.exr --resume " + dir + "/ck.clppm 2>&1", &out),
        0)
        << out;
    ASSERT_EQ(run_clppm(args + " --passes 8 -o " + dir + "/one.exr --resume " + dir + "/ck.clppm", &out), 0) << out;
    expect_same_pixels(dir + "/straight.exr", dir + "/three.exr");
    expect_same_pixels(dir + "/straight.exr", dir + "/one.exr");
}

namespace {

// Starts a long render on `ranks` ranks in the background, waits until its checkpoint shows a
// completed pass, and returns the directory; the job's output goes to dir/log, its status to
// dir/status.
std::string start_long_job(const std::string& tag, int ranks, int sigkill_timeout) {
    const std::string dir = make_temp_dir(tag);
    std::string out;
    // Warm PoCL's kernel cache first: PoCL links a kernel variant in a child process at its first
    // launch, and mpirun's SIGTERM reaches that child too, which makes PoCL abort (seen when this
    // test ran beside others that were filling the cache).
    run_clppm(std::string(kCommon) + " --integrator sppm --passes 3 -o " + dir + "/warm.exr", &out);
    // mpirun kills ranks `sigkill_timeout` s after its SIGTERM (default 1); a rank may be compiling
    // a kernel variant for a new photon count then (PoCL compiles one per work size at first
    // launch), so the Ctrl-C test gives it 10 s, as the README advises for slow writes.
    run_command("(mpirun --mca odls_base_sigkill_timeout " + std::to_string(sigkill_timeout) + mpirun(ranks).substr(6) +
                    kCommon + " --integrator sppm --passes 1000000 -o " + dir + "/job.exr --checkpoint " + dir +
                    "/ck.clppm --checkpoint-every 1 > " + dir + "/log 2>&1; echo $? > " + dir +
                    "/status) > /dev/null 2>&1 & echo $! > " + dir + "/shell.pid",
                &out);
    for (int i = 0; i < 1200 && !std::ifstream(dir + "/ck.clppm").good(); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    return dir;
}

// Seconds until dir/status appears (the job ended), at most `limit`.
double wait_for_end(const std::string& dir, double limit) {
    const auto t0 = std::chrono::steady_clock::now();
    for (;;) {
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (std::ifstream(dir + "/status").good() || s > limit) return s;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
}

// The pid of the clppm process of `rank` in the job writing dir/job.exr (from its environment).
int rank_pid(const std::string& dir, int rank) {
    std::string out;
    run_command("for p in $(pgrep -f 'clppm .*" + dir +
                    "/job.exr'); do tr '\\0' '\\n' < /proc/$p/environ 2>/dev/null "
                    "| grep -qx OMPI_COMM_WORLD_RANK=" +
                    std::to_string(rank) + " && echo $p; done",
                &out);
    return std::atoi(out.c_str());
}

void kill_job(const std::string& dir) {
    std::string out;
    run_command("pkill -KILL -f 'clppm .*" + dir + "/job.exr'; pkill -KILL -f 'mpirun .*" + dir + "/job.exr'; true",
                &out);
}

} // namespace

// Ctrl-C on mpirun: every rank stops, rank 0 writes the last complete pass and says so.
TEST(Mpi, CtrlCOnMpirunWritesTheLastPass) {
    REQUIRE_MPI();
    const std::string dir = start_long_job("mpi_ctrl_c", 2, 10);
    ASSERT_TRUE(std::ifstream(dir + "/ck.clppm").good()) << slurp(dir + "/log");
    std::string out;
    run_command("pkill -INT -f 'mpirun .*" + dir + "/job.exr'", &out);
    const double s = wait_for_end(dir, 30);
    const std::string log = slurp(dir + "/log");
    kill_job(dir);
    EXPECT_LT(s, 30) << "the job did not end: " << log;
    EXPECT_NE(log.find("the MPI job is ending"), std::string::npos) << log;
    EXPECT_NE(log.find("interrupted after pass"), std::string::npos) << log;
    const Image img = read_exr(dir + "/job.exr");
    EXPECT_EQ(img.attributes.at("clppm:interrupted"), "yes");
    EXPECT_GE(std::stoi(img.attributes.at("clppm:passes")), 1);
}

// A rank killed outright: the job ends within seconds (no rank waits for ever in a collective),
// mpirun names the rank, and rank 0 says the job is ending and writes its last complete pass.
TEST(Mpi, AKilledRankEndsTheJob) {
    REQUIRE_MPI();
    const std::string dir = start_long_job("mpi_kill", 3, 1);
    ASSERT_TRUE(std::ifstream(dir + "/ck.clppm").good()) << slurp(dir + "/log");
    const int victim = rank_pid(dir, 1);
    ASSERT_GT(victim, 0) << "no rank 1 found";
    ::kill(victim, SIGKILL);
    const double s = wait_for_end(dir, 30);
    const std::string log = slurp(dir + "/log");
    kill_job(dir);
    std::printf("the job ended %.1f s after rank 1 was killed\n", s);
    EXPECT_LT(s, 15) << log;
    EXPECT_NE(log.find("rank 1"), std::string::npos) << log;
    EXPECT_NE(log.find("the MPI job is ending"), std::string::npos) << log;
    EXPECT_NE(std::stoi(slurp(dir + "/status")), 0);
    EXPECT_GE(std::stoi(read_exr(dir + "/job.exr").attributes.at("clppm:passes")), 1);
}

// Ranks started with different arguments (mpirun's MPMD form) or given different scene files under
// one name (other working directories) crashed or hung; now the job ends at once with one error
// line from rank 0 naming what differs.
TEST(Mpi, RanksThatDifferAreOneErrorFromRankZero) {
    REQUIRE_MPI();
    const std::string dir = make_temp_dir("mpi_differ"), base = std::string(kCommon) + " --passes 2 -o ";
    const std::string mpirun1 = "timeout 120 mpirun --allow-run-as-root --oversubscribe ";
    auto expect_one_error = [](const std::string& out, const std::string& what) {
        const std::string line = "clppm: error: the 2 MPI processes were not started alike";
        EXPECT_NE(out.find(line), std::string::npos) << out;
        EXPECT_EQ(out.find(line), out.rfind(line)) << "one line, from rank 0:\n" << out;
        EXPECT_EQ(out.find("rank 1: error"), std::string::npos) << out;
        EXPECT_NE(out.find(what), std::string::npos) << out;
    };
    std::string out;
    const std::string a = clppm_binary() + " " + base + dir + "/a.exr";
    EXPECT_NE(run_command(mpirun1 + "-np 1 " + a + " : -np 1 " + a + " --width 64 --integrator pt 2>&1", &out), 0);
    EXPECT_EQ(out.find("status=124"), std::string::npos) << out;
    expect_one_error(out, "--width 48 on rank 0, 64 on rank 1");
    expect_one_error(out, "--integrator \"auto\" on rank 0, \"pt\" on rank 1");
    // --disc-coverage was missing from the list once (issue 61): it rendered with exit 0.
    EXPECT_NE(
        run_command(mpirun1 + "-np 1 " + a + " --disc-coverage on : -np 1 " + a + " --disc-coverage off 2>&1", &out),
        0);
    expect_one_error(out, "--disc-coverage \"on\" on rank 0, \"off\" on rank 1");
    // The same relative scene path, another file's contents on each rank.
    for (const char* sub : {"/r0", "/r1"}) {
        ASSERT_EQ(mkdir((dir + sub).c_str(), 0700), 0);
        std::ofstream(dir + sub + "/s.gltf")
            << slurp(std::string(CLPPM_TEST_DATA) + (sub[2] == '0' ? "/lights.gltf" : "/texture.gltf"));
    }
    const std::string s = clppm_binary() + " s.gltf " + base + dir + "/s.exr";
    EXPECT_NE(run_command(
                  mpirun1 + "-np 1 --wdir " + dir + "/r0 " + s + " : -np 1 --wdir " + dir + "/r1 " + s + " 2>&1", &out),
              0);
    expect_one_error(out, "the scene's contents (s.gltf)");
}

TEST(Cluster, LauncherProcessCountComesFromTheEnvironment) {
    EXPECT_EQ(launcher_process_count([](const char*) -> const char* { return nullptr; }), 0);
    EXPECT_EQ(launcher_process_count([](const char* n) -> const char* {
                  return std::string(n) == "OMPI_COMM_WORLD_SIZE" ? "3" : nullptr;
              }),
              3);
    EXPECT_EQ(launcher_process_count(
                  [](const char* n) -> const char* { return std::string(n) == "PMI_SIZE" ? "12" : nullptr; }),
              12);
    EXPECT_EQ(launcher_process_count([](const char*) -> const char* { return "x"; }), 0);
    // Without mpirun this process is a cluster of one.
    EXPECT_EQ(cluster().size(), 1);
    EXPECT_EQ(cluster().rank(), 0);
    EXPECT_EQ(cluster().prefix(), "");
}

// A build without MPI started by a launcher with several processes refuses, instead of rendering
// the whole image once per process (the launcher's environment stands in for mpirun here).
TEST(Cluster, ABuildWithoutMpiRefusesSeveralProcesses) {
    if (built_with_mpi()) GTEST_SKIP() << "built with MPI (the sanitizer build, CLPPM_MPI=OFF, runs this)";
    std::string out;
    const int rc = run_command("OMPI_COMM_WORLD_SIZE=2 " + clppm_binary() + " --width 8 --height 8 --passes 1 -o " +
                                   make_temp_dir("nompi") + "/x.exr 2>&1",
                               &out);
    EXPECT_NE(rc, 0);
    EXPECT_NE(out.find("built without MPI"), std::string::npos) << out;
    EXPECT_NE(out.find("2 copies"), std::string::npos) << out;
}

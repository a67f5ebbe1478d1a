// The glTF loader against hostile input, without sanitizers and fast enough for every test run:
// one small file per defect found (tests/fuzz/regressions/), the hostile-value files of
// tests/fuzz/hostile/ (written by tests/fuzz/make_hostile.py, which explains each one), and
// deterministic mutations of the seeds. Every input must load into a Scene the renderer can use or
// throw a clppm::Error of one line that starts with the file path, within a time bound: a hang is
// a failure. The bound (2 s per file, against a few milliseconds normally) guards against hangs,
// not performance, so it is generous. tests/fuzz/README.md describes the fuzzer itself.
#include "scene/gltf/gltf_load.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "test_util.h"
#include "util/error.h"

namespace clppm {
namespace {

namespace fs = std::filesystem;

// Far beyond any load's time: only a hang (or a quadratic blow-up) reaches it. Scaled by
// CLPPM_TEST_TIME_SCALE, which the sanitizer build sets (test_util.h).
const double kHangSeconds = 2.0 * test::time_scale();

fs::path fuzz_dir() { return (fs::path(CLPPM_TEST_DATA) / ".." / "fuzz").lexically_normal(); }

std::string read_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

void write_bytes(const fs::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

std::vector<fs::path> files_in(const fs::path& dir, const std::vector<std::string>& extensions) {
    std::vector<fs::path> files;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        std::string ext = entry.path().extension().string();
        if (entry.is_regular_file() &&
            (extensions.empty() || std::find(extensions.begin(), extensions.end(), ext) != extensions.end()))
            files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

bool finite3(const float* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

// What the renderer relies on in a loaded Scene (tests/fuzz/gltf_fuzz.cpp checks the same).
void expect_usable(const Scene& s, const std::string& what) {
    SCOPED_TRACE(what);
    ASSERT_GT(s.num_triangles(), 0u);
    ASSERT_EQ(s.positions.size(), 3 * s.shading.size());
    for (const Vec3& p : s.positions) ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    for (const dev::TriShading& t : s.shading) {
        ASSERT_LT(t.material, s.materials.size());
        ASSERT_TRUE(finite3(t.n0) && finite3(t.n1) && finite3(t.n2));
    }
    for (const dev::Material& m : s.materials) {
        ASSERT_LT(m.base_color_tex, int32_t(s.textures.size()));
        ASSERT_TRUE(finite3(m.base_color) && finite3(m.emission));
    }
    for (const dev::Texture& t : s.textures)
        ASSERT_LE(uint64_t(t.offset) + uint64_t(t.width) * t.height, s.texels.size());
    for (const dev::Light& l : s.punctual_lights)
        ASSERT_TRUE(finite3(l.position) && finite3(l.radiance) && std::isfinite(l.power));
}

struct Outcome {
    bool loaded = false;
    Scene scene;
    std::string error; // the message, when !loaded
    double seconds = 0;
};

// Loads `path`, failing the test on a slow load, an exception that is not a clppm::Error, a
// message that is not one line starting with the path, or an unusable Scene.
Outcome load_checked(const fs::path& path) {
    Outcome r;
    auto t0 = std::chrono::steady_clock::now();
    try {
        r.scene = load_gltf(path.string());
        r.loaded = true;
    } catch (const Error& e) {
        r.error = e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << path << ": not a clppm::Error: " << e.what();
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_LT(r.seconds, kHangSeconds) << path << " took " << r.seconds << " s";
    if (r.loaded) {
        expect_usable(r.scene, path.string());
    } else if (!r.error.empty()) {
        EXPECT_EQ(r.error.rfind(path.string() + ": ", 0), 0u) << r.error;
        EXPECT_EQ(r.error.find_first_of("\r\n"), std::string::npos) << r.error;
    }
    return r;
}

// A private copy of tests/fuzz/hostile/ laid out as make_hostile.py describes:
//   root/outside.bin       a valid buffer: a URI that escaped the scene directory would load
//   root/scene/            the hostile files, external.bin, sub/, and the symbolic links
//                          link_out.bin -> ../outside.bin, link_dir -> .., link_in.bin -> external.bin
struct HostileDir {
    fs::path root, scene;
    HostileDir() {
        root = test::make_temp_dir("fuzz_regression");
        scene = root / "scene";
        fs::create_directories(scene / "sub");
        for (const fs::path& f : files_in(fuzz_dir() / "hostile", {})) fs::copy_file(f, scene / f.filename());
        fs::copy_file(scene / "external.bin", root / "outside.bin");
        fs::create_symlink("../outside.bin", scene / "link_out.bin");
        fs::create_symlink("..", scene / "link_dir");
        fs::create_symlink("external.bin", scene / "link_in.bin");
    }
    ~HostileDir() {
        std::error_code ec;
        fs::remove_all(root, ec);
    }
    fs::path operator/(const std::string& name) const { return scene / name; }
};

// ---- regression corpus ------------------------------------------------------------------------

// What the files make_hostile.py wrote for the defects found fail with now (README.md tells each
// defect and its fix). A file added to regressions/ by hand need not be listed: it must load or
// fail cleanly like any other.
const std::map<std::string, const char*> kRegressionExpected = {
    {"glb_bin_chunk_past_end.glb", "invalid GLB: BIN chunk past the end of the file"},
    {"image_buffer_view_index_wraps.gltf", "image 0 bufferView 4294967296 is not a valid index"},
    {"image_buffer_view_negative_index_wraps.gltf", "image 0 bufferView -4294967296 is not a valid index"},
    {"buffer_view_buffer_index_wraps.gltf", "bufferView 0 buffer 4294967296 is not a valid index"},
    {"emission_product_overflow.gltf", "material 0 has a non-finite emissiveFactor * emissiveStrength"},
    {"point_light_power_overflow.gltf", "light 0 has a non-finite power"},
    {"spot_light_power_overflow.gltf", "light 0 has a non-finite power"},
    {"symlink_file_escape.gltf", "link_out.bin: a symbolic link that leads outside the scene directory"},
    {"symlink_dir_escape.gltf", "outside.bin: a symbolic link that leads outside the scene directory"},
    {"triangle_instancing_bomb.gltf", "the scene has more than 2^25 triangles"},
    // A URI with a newline made a two-line message; file text is now escaped ("\n").
    {"uri_with_newline_in_message.gltf", "buffer 0 URI 'data:applicatio>n/oct\\n.parse_error.101]"},
};

TEST(FuzzRegressions, EveryFindingLoadsOrFailsCleanly) {
    std::vector<fs::path> files = files_in(fuzz_dir() / "regressions", {});
    ASSERT_FALSE(files.empty()) << "no files in " << fuzz_dir() / "regressions";
    HostileDir dir; // each runs from a scene directory, beside the canary and the links
    size_t listed = 0;
    for (const fs::path& f : files) {
        fs::path copy = dir / f.filename().string();
        fs::copy_file(f, copy, fs::copy_options::overwrite_existing);
        Outcome r = load_checked(copy);
        auto want = kRegressionExpected.find(f.filename().string());
        if (want == kRegressionExpected.end()) continue;
        ++listed;
        EXPECT_FALSE(r.loaded) << f << " loaded";
        EXPECT_NE(r.error.find(want->second), std::string::npos) << "expected '" << want->second << "' in: " << r.error;
    }
    EXPECT_EQ(listed, kRegressionExpected.size()) << "a listed regression file is missing";
}

// ---- hostile values: the expected outcome of every file make_hostile.py writes -----------------

// nullptr: loads; otherwise the error holds this text.
const std::map<std::string, const char*> kHostileExpected = {
    {"accessor_count_negative.gltf", "'count' property is not a positive integer"},
    {"accessor_count_times_stride.gltf", "accessor 0 reads past the end of bufferView 0"},
    {"accessor_count_u64_max.gltf", "count 18446744073709551615 exceeds the limit of 2^31"},
    {"accessor_offset_u64_max.gltf", "accessor 0 reads past the end of bufferView 0"},
    {"accessor_offset_wraps.gltf", "accessor 0 reads past the end of bufferView 0"},
    {"accessor_sparse.gltf", "accessor 0 sparse count 1000 is not in 1..3"},
    {"accessor_sparse_values_past_view.gltf", "accessor 0 sparse values reads past the end of bufferView 2"},
    {"accessor_type_mat4_position.gltf", "accessor 0 reads past the end of bufferView 0"},
    {"buffer_length_petabyte.gltf", "Failed to decode 'uri'"},
    {"buffer_length_short.gltf", "Failed to decode 'uri'"},
    {"camera_aperture_overflow.gltf", "extras.aperture_radius must be a number >= 0"},
    {"camera_aspect_overflow.gltf", "has an invalid aspectRatio"},
    {"camera_yfov_overflow.gltf", "yfov must lie in (0, pi)"},
    {"child_negative.gltf", "child node -1 out of range"},
    {"cycle_self.gltf", "node graph cycle: node 0 ('tri') is its own ancestor"},
    {"cycle_unreachable.gltf", nullptr},
    {"cycle_without_scenes.gltf", nullptr},
    {"dag_shared_child.gltf", nullptr},
    {"default_scene_out_of_range.gltf", "default scene 4 out of range"},
    {"factor_base_color_overflow.gltf", "non-finite baseColorFactor"},
    {"factor_base_color_wrong_length.gltf", nullptr}, // tinygltf keeps the default (1,1,1,1)
    {"factor_emissive_overflow.gltf", "non-finite emissiveFactor"},
    {"factor_emissive_strength_overflow.gltf", "non-finite emissiveStrength"},
    {"factor_ior_overflow.gltf", "non-finite ior"},
    {"factor_metallic_overflow.gltf", "non-finite metallicFactor"},
    {"factor_roughness_overflow.gltf", "non-finite roughnessFactor"},
    {"factor_transmission_overflow.gltf", "non-finite transmissionFactor"},
    {"glb_bin_length_huge.glb", "invalid GLB: BIN chunk past the end of the file"},
    {"glb_bin_length_unaligned.glb", "invalid glTF"},
    {"glb_header_only.glb", "invalid GLB: no JSON chunk"},
    {"glb_json_length_huge.glb", "invalid GLB: JSON chunk past the end of the file"},
    {"glb_json_length_zero.glb", "invalid GLB"}, // the JSON text is then read as a chunk header
    {"glb_total_length_huge.glb", "Invalid glTF binary"},
    {"glb_total_length_short.glb", "Invalid glTF binary"},
    {"glb_version_1.glb", nullptr}, // tinygltf reads the container regardless of the version
    {"image_claims_16384_square.gltf", nullptr},
    {"image_claims_1e5_by_1e5.gltf", nullptr},
    {"image_claims_8192_square_truncated.gltf", nullptr},
    {"index_float_type.gltf", "accessor 2 reads past the end of bufferView 2"},
    {"index_u32_max.gltf", "reference vertex 4294967295 beyond the 3 vertices"},
    {"index_u8_out_of_range.gltf", "reference vertex 200 beyond the 3 vertices"},
    {"light_color_wrong_length.gltf", "light 0 color must have 3 components"},
    {"light_index_out_of_range.gltf", "light 7 out of range (1 lights)"},
    {"light_intensity_overflow.gltf", "light 0 has a non-finite color or intensity"},
    {"node_instancing_bomb.gltf", "the node hierarchy instances more than 2^20 nodes"},
    {"node_matrix_overflow.gltf", "no triangle geometry"}, // finite matrix, every corner overflows
    {"node_matrix_wrong_length.gltf", "has a transform array of the wrong length"},
    {"node_rotation_zero_quaternion.gltf", "node 0 ('tri') has a non-finite transform"},
    {"node_scale_wrong_length.gltf", "has a transform array of the wrong length"},
    {"node_translation_huge.gltf", "no triangle geometry"},
    {"normals_inf_zero_huge.gltf", nullptr},
    {"normals_singular_transform.gltf", nullptr},
    {"positions_all_nonfinite.gltf", "no triangle geometry"},
    {"positions_overflow_in_world_space.gltf", nullptr},
    {"scene_root_out_of_range.gltf", "scene root node 3 out of range"},
    {"uri_backslash_absolute.gltf", "points outside the scene directory"},
    {"uri_backslash_parent.gltf", "File not found : ..\\outside.bin"}, // one file name on POSIX
    {"uri_directory.gltf", "File not found : sub"},
    {"uri_dot.gltf", "File not found : ."},
    {"uri_dot_dot_only.gltf", "URI '..' points outside the scene directory"},
    {"uri_double_encoded.gltf", "File not found : %2e%2e/outside.bin"}, // decoded once, not twice
    {"uri_file_scheme.gltf", "is not a relative file path"},
    {"uri_http.gltf", "is not a relative file path"},
    {"uri_nul_byte.gltf", "contains control characters"},
    {"uri_percent_all.gltf", "points outside the scene directory"},
    {"uri_percent_dots.gltf", "URI '%2e%2e/outside.bin' points outside the scene directory"},
    {"uri_percent_dots_upper.gltf", "points outside the scene directory"},
    {"uri_plain_inside.gltf", nullptr},
    {"uri_shell_expansion.gltf", "File not found : $(touch pwned)"},
    {"uri_sub_dot_dot_inside.gltf", nullptr},
    {"uri_symlink_dir_out.gltf", "a symbolic link that leads outside the scene directory"},
    {"uri_symlink_inside.gltf", nullptr},
    {"uri_symlink_out.gltf", "a symbolic link that leads outside the scene directory"},
    {"uri_tilde.gltf", "File not found : ~/outside.bin"},
    {"view_buffer_out_of_range.gltf", "bufferView 0 buffer 5 out of range"},
    {"view_length_u64_max.gltf", "bufferView 0 extends past the end of buffer 0"},
    {"view_offset_u64_max.gltf", "bufferView 0 extends past the end of buffer 0"},
    {"view_stride_too_small.gltf", "byteStride 4 does not fit accessor 0"},
};

TEST(FuzzHostile, EveryFileHasItsExpectedOutcome) {
    HostileDir dir;
    std::vector<fs::path> files = files_in(fuzz_dir() / "hostile", {".gltf", ".glb"});
    ASSERT_EQ(files.size(), kHostileExpected.size()) << "a file of tests/fuzz/hostile/ without an expectation here";
    for (const fs::path& f : files) {
        auto want = kHostileExpected.find(f.filename().string());
        ASSERT_NE(want, kHostileExpected.end()) << f << " has no expectation";
        Outcome r = load_checked(dir / f.filename().string());
        if (want->second) {
            EXPECT_FALSE(r.loaded) << f << " loaded";
            EXPECT_NE(r.error.find(want->second), std::string::npos)
                << "expected '" << want->second << "' in: " << r.error;
        } else {
            EXPECT_TRUE(r.loaded) << f << ": " << r.error;
        }
    }
}

void expect_normal(const float* n, double x, double y, double z) {
    EXPECT_NEAR(n[0], x, 1e-6);
    EXPECT_NEAR(n[1], y, 1e-6);
    EXPECT_NEAR(n[2], z, 1e-6);
}

// A hostile file that must load, from its own scene directory: its scene, which must hold
// `triangles` triangles (a fatal failure otherwise; call under ASSERT_NO_FATAL_FAILURE).
void load_accepted(const char* name, size_t triangles, Scene* scene) {
    HostileDir dir;
    Outcome r = load_checked(dir / name);
    ASSERT_TRUE(r.loaded) << r.error;
    ASSERT_EQ(r.scene.num_triangles(), triangles);
    *scene = std::move(r.scene);
}

TEST(FuzzHostile, PositionsThatOverflowInWorldSpaceAreSkippedAndCounted) {
    Scene s;
    ASSERT_NO_FATAL_FAILURE(load_accepted("positions_overflow_in_world_space.gltf", 1, &s));
    EXPECT_EQ(s.degenerate_triangles_skipped, 1u);
}

TEST(FuzzHostile, InfiniteZeroAndHugeNormals) {
    Scene s;
    ASSERT_NO_FATAL_FAILURE(load_accepted("normals_inf_zero_huge.gltf", 3, &s));
    EXPECT_EQ(s.degenerate_triangles_skipped, 0u);
    // +Inf and zero normals give way to the flat normal; 1e38 components normalise in double.
    for (size_t t = 0; t < 2; ++t) {
        expect_normal(s.shading[t].n0, 0, 0, 1);
        expect_normal(s.shading[t].n2, 0, 0, 1);
    }
    double c = 1 / std::sqrt(3.0);
    expect_normal(s.shading[2].n1, c, c, c);
}

TEST(FuzzHostile, SingularTransformFallsBackToFlatNormals) {
    Scene s;
    ASSERT_NO_FATAL_FAILURE(load_accepted("normals_singular_transform.gltf", 1, &s));
    expect_normal(s.shading[0].n0, 0, 0, 1); // the file says (0, .6, .8)
}

TEST(FuzzHostile, AcyclicSharingAndUnreachableCycles) {
    HostileDir dir;
    Outcome dag = load_checked(dir / "dag_shared_child.gltf");
    ASSERT_TRUE(dag.loaded) << dag.error;
    ASSERT_EQ(dag.scene.num_triangles(), 2u);
    EXPECT_NEAR(dag.scene.positions[3].z, 1.f, 1e-6); // second instance under the translated parent
    EXPECT_EQ(load_checked(dir / "cycle_unreachable.gltf").scene.num_triangles(), 1u);
    EXPECT_EQ(load_checked(dir / "cycle_without_scenes.gltf").scene.num_triangles(), 1u);
}

TEST(FuzzHostile, ImagesThatClaimHugeSizesAreIgnoredWithAWarning) {
    HostileDir dir;
    for (const char* name : {"image_claims_1e5_by_1e5.gltf", "image_claims_16384_square.gltf",
                             "image_claims_8192_square_truncated.gltf"}) {
        Outcome r = load_checked(dir / name);
        ASSERT_TRUE(r.loaded) << r.error;
        EXPECT_TRUE(r.scene.textures.empty()) << name;
        EXPECT_EQ(r.scene.materials.at(0).base_color_tex, -1) << name;
        bool warned = false;
        for (const std::string& w : r.scene.warnings) warned |= w.find("texture ignored") != std::string::npos;
        EXPECT_TRUE(warned) << name << ": " << ::testing::PrintToString(r.scene.warnings);
    }
}

TEST(FuzzHostile, UrisAreNeverShellExpanded) {
    HostileDir dir;
    fs::path cwd = fs::current_path();
    load_checked(dir / "uri_shell_expansion.gltf");
    EXPECT_FALSE(fs::exists(cwd / "pwned"));
    EXPECT_FALSE(fs::exists(dir.scene / "pwned"));
    EXPECT_FALSE(fs::exists(dir.root / "pwned"));
}

TEST(FuzzHostile, SymbolicLinksMayNotLeadOutOfTheSceneDirectory) {
    HostileDir dir;
    EXPECT_TRUE(load_checked(dir / "uri_symlink_inside.gltf").loaded);
    EXPECT_NE(load_checked(dir / "uri_symlink_out.gltf").error.find("symbolic link"), std::string::npos);
    EXPECT_NE(load_checked(dir / "uri_symlink_dir_out.gltf").error.find("symbolic link"), std::string::npos);
    // A scene directory reached through a link is fine: links are resolved on both sides.
    fs::path alias = dir.root / "alias";
    fs::create_directory_symlink("scene", alias);
    EXPECT_TRUE(load_checked(alias / "uri_plain_inside.gltf").loaded);
    EXPECT_TRUE(load_checked(alias / "uri_symlink_inside.gltf").loaded);
}

// Built in memory: thirty thousand nodes is no file to keep.
TEST(FuzzHostile, ChainOfThirtyThousandNodesLoadsWithoutRecursion) {
    HostileDir dir;
    nlohmann::json doc = nlohmann::json::parse(read_bytes(dir / "uri_plain_inside.gltf"));
    const int n = 30000;
    nlohmann::json nodes = nlohmann::json::array();
    for (int i = 0; i < n; ++i) nodes.push_back({{"children", {i + 1}}});
    nodes.push_back({{"mesh", 0}, {"translation", {0, 0, 1}}});
    doc["nodes"] = nodes;
    doc["scenes"] = {{{"nodes", {0}}}};
    fs::path path = dir / "chain.gltf";
    write_bytes(path, doc.dump());
    Outcome r = load_checked(path);
    ASSERT_TRUE(r.loaded) << r.error;
    EXPECT_EQ(r.scene.num_triangles(), 1u);
}

// Absurd sizes fail (or load without the absurd part) before a large allocation: the loads run
// in a child process whose address space is capped at 512 MiB above what it already has, where a
// large allocation throws std::bad_alloc (not a clppm::Error) or kills the child.
TEST(FuzzHostile, AbsurdSizesFailWithoutALargeAllocation) {
    HostileDir dir;
    fs::copy_file(fuzz_dir() / "regressions" / "triangle_instancing_bomb.gltf", dir / "triangle_bomb.gltf");
    const char* files[] = {"triangle_bomb.gltf",
                           "node_instancing_bomb.gltf",
                           "accessor_count_u64_max.gltf",
                           "accessor_count_times_stride.gltf",
                           "buffer_length_petabyte.gltf",
                           "view_length_u64_max.gltf",
                           "glb_bin_length_huge.glb",
                           "glb_json_length_huge.glb",
                           "glb_total_length_huge.glb",
                           "image_claims_1e5_by_1e5.gltf",
                           "image_claims_16384_square.gltf"};
    // Not image_claims_8192_square_truncated.gltf: 8192^2 texels is inside the loader's 2^26
    // texel budget, so stb_image may allocate its 256 MiB before it finds the data missing.
    std::ifstream statm("/proc/self/statm");
    uint64_t pages = 0;
    statm >> pages;
    ASSERT_GT(pages, 0u);
    pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        uint64_t limit = pages * uint64_t(sysconf(_SC_PAGESIZE)) + (uint64_t(512) << 20);
        rlimit rl{limit, limit};
        if (setrlimit(RLIMIT_AS, &rl) != 0) _exit(3);
        int status = 0;
        for (const char* name : files) {
            try {
                load_gltf((dir / name).string());
            } catch (const Error&) {
            } catch (const std::bad_alloc&) {
                status = 2;
            } catch (...) {
                status = status ? status : 5;
            }
        }
        _exit(status);
    }
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status)) << "the child died of signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    EXPECT_EQ(WEXITSTATUS(status), 0) << "2: std::bad_alloc, 3: setrlimit failed, 5: another exception";
}

// ---- deterministic mutations of the seeds ---------------------------------------------------

// Tokens that make glTF hostile: the fuzzer's dictionary (tests/fuzz/gltf.dict) in short.
const char* const kTokens[] = {"-1",
                               "0",
                               "4294967295",
                               "4294967296",
                               "2147483648",
                               "18446744073709551615",
                               "1e39",
                               "-1e39",
                               "1e308",
                               "3.4e38",
                               "1e-45",
                               "null",
                               "true",
                               "[]",
                               "{}",
                               "\"\"",
                               "\"../outside.bin\"",
                               "\"%2e%2e/outside.bin\"",
                               "\"/etc/passwd\"",
                               "\"external.bin\"",
                               "\"link_out.bin\"",
                               "\"children\":[0],",
                               "\"scene\":9,",
                               "\"byteStride\":252,",
                               "\"sparse\":{},",
                               "\"mode\":4,",
                               "\"count\":99999999,",
                               "\"byteOffset\":4294967295,",
                               "\"KHR_lights_punctual\"",
                               "\"extensionsRequired\":[\"x\"],"};

struct Mutator {
    uint64_t state;
    uint32_t next() {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return uint32_t(state >> 33);
    }
    size_t below(size_t n) { return n ? next() % n : 0; }

    // The start of the number nearest after i, or npos.
    static size_t number_at(const std::string& s, size_t i) {
        while (i < s.size() && !(std::isdigit((unsigned char)s[i]) || s[i] == '-')) ++i;
        return i < s.size() ? i : std::string::npos;
    }

    std::string mutate(std::string s) {
        if (s.empty()) return s;
        switch (below(6)) {
        case 0: { // a number replaced by a hostile one
            size_t i = number_at(s, below(s.size()));
            if (i == std::string::npos) break;
            size_t j = i + 1;
            auto in_number = [&](char c) { return std::isdigit((unsigned char)c) || c == '.' || c == 'e' || c == '-'; };
            while (j < s.size() && in_number(s[j])) ++j;
            s.replace(i, j - i, kTokens[below(10)]);
            break;
        }
        case 1: { // a token inserted after a '{', ',' or ':'
            size_t i = s.find_first_of("{,:", below(s.size()));
            if (i != std::string::npos) s.insert(i + 1, kTokens[below(std::size(kTokens))]);
            break;
        }
        case 2: // a little-endian u32 overwritten, often a GLB field: total length (8), JSON
            // chunk length (12) and type (16), BIN chunk length (20 + JSON chunk length)
            if (s.size() >= 24) {
                size_t bin = 20;
                for (int k = 0; k < 4; ++k) bin += size_t(uint8_t(s[12 + size_t(k)])) << (8 * k);
                size_t fields[] = {8, 12, 16, bin + 8 <= s.size() ? bin : 8};
                size_t at = below(5) < 4 ? fields[below(4)] : below(s.size() - 4);
                uint32_t v[] = {0u, 1u, 0xFFFFFFFFu, 0x7FFFFFFFu, uint32_t(s.size()), uint32_t(s.size() + 4)};
                uint32_t x = v[below(std::size(v))];
                for (int k = 0; k < 4; ++k) s[at + size_t(k)] = char((x >> (8 * k)) & 0xFF);
            }
            break;
        case 3: // bytes flipped
            for (int k = 0; k < 3; ++k) s[below(s.size())] ^= char(1u << below(8));
            break;
        case 4: { // a span copied over another place (crossover within the file)
            size_t a = below(s.size()), b = below(s.size()), n = std::min(below(64) + 1, s.size() - std::max(a, b));
            s.replace(b, n, s.substr(a, n));
            break;
        }
        default: s.resize(below(s.size())); break;
        }
        return s;
    }
};

TEST(FuzzMutations, MutatedSeedsLoadOrFailCleanlyAndQuickly) {
    HostileDir dir;
    std::vector<fs::path> seeds;
    for (const fs::path& f : files_in(CLPPM_TEST_DATA, {".gltf", ".glb"}))
        if (fs::file_size(f) < 16384) seeds.push_back(f);
    seeds.push_back(fs::path(CLPPM_SCENES_DIR) / "plane_point_light.gltf");
    for (const char* name : {"uri_plain_inside.gltf", "dag_shared_child.gltf", "normals_inf_zero_huge.gltf",
                             "light_intensity_overflow.gltf", "image_claims_16384_square.gltf"})
        seeds.push_back(fuzz_dir() / "hostile" / name);
    for (const fs::path& f : files_in(fuzz_dir() / "regressions", {})) seeds.push_back(f);

    Mutator m{20240601};
    const int kPerSeed = 12; // a few hundred in all
    int loaded = 0, failed = 0;
    for (const fs::path& seed : seeds) {
        std::string original = read_bytes(seed);
        for (int i = 0; i < kPerSeed; ++i) {
            std::string bytes = m.mutate(original);
            if (m.below(3) == 0) bytes = m.mutate(bytes); // sometimes two steps
            fs::path path = dir / ("mutated" + seed.extension().string());
            write_bytes(path, bytes);
            SCOPED_TRACE(seed.filename().string() + " mutation " + std::to_string(i));
            bool failing_before = HasFailure();
            Outcome r = load_checked(path);
            (r.loaded ? loaded : failed) += 1;
            if (!failing_before && HasFailure()) { // keep the first failing input for the corpus
                fs::path keep = dir.root.parent_path() / "clppm_fuzz_regression_failure.bin";
                write_bytes(keep, bytes);
                FAIL() << "input kept as " << keep;
            }
        }
    }
    EXPECT_GT(seeds.size() * kPerSeed, 300u);
    EXPECT_GT(loaded, 0);
    EXPECT_GT(failed, 0);
}

} // namespace
} // namespace clppm

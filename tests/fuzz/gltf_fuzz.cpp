// libFuzzer target for the glTF loader (src/scene/gltf/). Built by tests/fuzz/build.sh with
// -fsanitize=fuzzer,address,undefined; run by tests/fuzz/run.sh (see tests/fuzz/README.md).
//
// Every input goes through the loader three ways:
//   1. load_gltf_text(bytes, "", name)        in-memory text (or GLB: the loader sniffs the magic),
//                                              no directory: external URIs must be refused;
//   2. load_gltf_text(bytes, scene_dir, name) the same with a directory holding real files (only
//                                              when way 1 failed on an external URI: otherwise
//                                              the directory is never used and 2 repeats 1);
//   3. load_gltf(glb_dir/input.glb)           the bytes as a file on disk, the CLI's path.
// Only clppm::Error may leave the loader, and its message must be one line that starts with the
// display name. Anything else is a finding: another exception type (libFuzzer reports the abort
// from std::terminate), a crash or sanitizer report, a timeout, an OOM, a Scene that breaks the
// invariants the renderer relies on (checked below), or a file opened outside the scene
// directories (an inotify watch on their parent holds canary files that must never be opened).
#include <sys/inotify.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "scene/gltf/gltf_load.h"
#include "scene/scene.h"
#include "util/error.h"

namespace {

namespace fs = std::filesystem;

[[noreturn]] void finding(const std::string& what) {
    std::fprintf(stderr, "\n==gltf_fuzz== FINDING: %s\n", what.c_str());
    std::fflush(stderr);
    std::abort();
}

void write_file(const std::string& path, const void* data, size_t size) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(static_cast<const char*>(data), std::streamsize(size));
    if (!out) finding("cannot write " + path);
}

// A private temporary tree, made once per process:
//   root/           canaries outside.bin, secret.png (opening either is a finding)
//   root/scene/     base directory of way 2: external.bin (108 bytes of the seeds'
//                   tests/data/external.gltf), image.png, sub/ (for "sub/../x" URIs), and the
//                   symlinks of tests/fuzz/make_hostile.py: link_out.bin -> ../outside.bin,
//                   link_dir -> .., link_in.bin -> external.bin, and link_out.png -> ../secret.png
//   root/glb/       input.glb, way 3's file and base directory
struct Sandbox {
    std::string root, scene_dir, glb_path;
    int inotify_fd = -1;

    Sandbox() {
        const char* tmp = std::getenv("TMPDIR");
        std::string tmpl = std::string(tmp && *tmp ? tmp : "/tmp") + "/clppm_gltf_fuzz_XXXXXX";
        std::vector<char> buf(tmpl.begin(), tmpl.end());
        buf.push_back('\0');
        if (!mkdtemp(buf.data())) finding("mkdtemp failed for " + tmpl);
        root = buf.data();
        scene_dir = root + "/scene";
        glb_path = root + "/glb/input.glb";
        fs::create_directories(scene_dir + "/sub");
        fs::create_directories(root + "/glb");
        copy_external_bin();
        static const unsigned char png_1x1[] = {
            // one RGBA texel (255, 128, 64, 255)
            0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
            0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00, 0x00, 0x1f, 0x15, 0xc4, 0x89, 0x00, 0x00, 0x00,
            0x0d, 0x49, 0x44, 0x41, 0x54, 0x78, 0xda, 0x63, 0xf8, 0xdf, 0xe0, 0xf0, 0x1f, 0x00, 0x07, 0x00, 0x02, 0xbf,
            0xf4, 0x89, 0xd5, 0xf2, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
        write_file(scene_dir + "/image.png", png_1x1, sizeof(png_1x1));
        // The canaries hold a valid buffer / image, so a URI that escapes would load, not fail.
        write_file(root + "/outside.bin", std::string(108, '\0').data(), 108);
        write_file(root + "/secret.png", png_1x1, sizeof(png_1x1));
        fs::create_symlink("../outside.bin", scene_dir + "/link_out.bin");
        fs::create_symlink("..", scene_dir + "/link_dir");
        fs::create_symlink("external.bin", scene_dir + "/link_in.bin");
        fs::create_symlink("../secret.png", scene_dir + "/link_out.png");
        inotify_fd = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
        if (inotify_fd < 0 || inotify_add_watch(inotify_fd, root.c_str(), IN_OPEN) < 0)
            finding(std::string("inotify: ") + std::strerror(errno));
    }

    ~Sandbox() {
        std::error_code ec;
        fs::remove_all(root, ec);
    }

    void copy_external_bin() {
#ifdef CLPPM_TEST_DATA
        std::error_code ec;
        fs::copy_file(std::string(CLPPM_TEST_DATA) + "/external.bin", scene_dir + "/external.bin", ec);
        if (!ec) return;
#endif
        write_file(scene_dir + "/external.bin", std::string(108, '\0').data(), 108);
    }

    // Opens of files directly inside root/ (the canaries); opens in scene/ and glb/ are not seen.
    void check_no_escape(const std::string& way) {
        alignas(inotify_event) char buf[4096];
        ssize_t n;
        while ((n = read(inotify_fd, buf, sizeof buf)) > 0) {
            for (char* p = buf; p < buf + n;) {
                auto* ev = reinterpret_cast<inotify_event*>(p);
                if (!(ev->mask & IN_ISDIR) && ev->len)
                    finding(way + ": the loader opened " + root + "/" + ev->name + ", outside the scene directory");
                p += sizeof(inotify_event) + ev->len;
            }
        }
    }
};

Sandbox& sandbox() {
    static Sandbox s;
    return s;
}

bool finite3(const float* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

// What the renderer assumes of every loaded Scene.
void check_scene(const clppm::Scene& s, const std::string& way) {
    auto require = [&](bool ok, const std::string& what) {
        if (!ok) finding(way + ": loaded Scene breaks an invariant: " + what);
    };
    require(s.num_triangles() > 0, "no triangles");
    require(s.positions.size() == 3 * s.shading.size(), "positions != 3 * triangles");
    for (const clppm::Vec3& p : s.positions)
        require(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z), "non-finite position");
    for (const clppm::dev::TriShading& t : s.shading) {
        require(t.material < s.materials.size(), "material index out of range");
        require(finite3(t.n0) && finite3(t.n1) && finite3(t.n2), "non-finite normal");
        for (const float* uv : {t.uv0, t.uv1, t.uv2})
            require(std::isfinite(uv[0]) && std::isfinite(uv[1]), "non-finite uv");
    }
    for (const clppm::dev::Material& m : s.materials) {
        require(m.base_color_tex < int32_t(s.textures.size()), "texture index out of range");
        require(finite3(m.base_color) && finite3(m.emission), "non-finite material colour");
        require(std::isfinite(m.metallic) && std::isfinite(m.roughness) && std::isfinite(m.ior), "non-finite factor");
    }
    for (const clppm::dev::Texture& t : s.textures)
        require(t.width > 0 && t.height > 0 && uint64_t(t.offset) + uint64_t(t.width) * t.height <= s.texels.size(),
                "texture outside the texel array");
    for (const clppm::dev::Light& l : s.punctual_lights)
        require(finite3(l.position) && finite3(l.direction) && finite3(l.radiance) && std::isfinite(l.power),
                "non-finite light");
    for (const clppm::CameraDesc& c : s.cameras)
        require(finite3(c.position) && finite3(c.forward) && finite3(c.up) && std::isfinite(c.yfov),
                "non-finite camera");
}

void check_error(const clppm::Error& e, const std::string& name, const std::string& way) {
    std::string msg = e.what();
    if (msg.rfind(name + ": ", 0) != 0) finding(way + ": error does not start with '" + name + ": ': " + msg);
    if (msg.find_first_of("\r\n") != std::string::npos) finding(way + ": error is not one line: " + msg);
}

// Returns the error message, empty when the input loaded.
template <typename Load>
std::string attempt(const std::string& name, const std::string& way, Load load) {
    std::string message;
    try {
        clppm::Scene s = load();
        check_scene(s, way);
    } catch (const clppm::Error& e) {
        check_error(e, name, way);
        message = e.what();
    }
    sandbox().check_no_escape(way);
    return message;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    Sandbox& box = sandbox();
    std::string text(reinterpret_cast<const char*>(data), size);
    const std::string name = "fuzz input";
    std::string no_dir =
        attempt(name, "text without a directory", [&] { return clppm::load_gltf_text(text, "", name); });
    // The directory matters only to a file that names an external file, which fails without one
    // (before anything else is read): otherwise way 2 would repeat way 1 step for step.
    if (no_dir.find("names an external file") != std::string::npos)
        attempt(name, "text in a directory", [&] { return clppm::load_gltf_text(text, box.scene_dir, name); });
    write_file(box.glb_path, data, size);
    attempt(box.glb_path, "file", [&] { return clppm::load_gltf(box.glb_path); });
    return 0;
}

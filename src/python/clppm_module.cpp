// The Python module's native part, _clppm (python/clppm/__init__.py is its face): the render loop
// of render/render_loop.h with the observers the options ask for, as the command line runs it,
// stepped from Python. Options arrive as ("--name", "value") pairs and go through the command
// line's option table, so they take the same values, defaults and one-line messages; a render
// with the same options, seed and device is the command line's, bit for bit.
//
// Long calls release the GIL. While they run in the main thread, SIGINT (Ctrl-C) asks the render
// to stop at its next photon batch, as on the command line (util/cancellation.h), and the call
// returns False; the Python side raises KeyboardInterrupt (clppm.Interrupted) with the last
// complete pass kept.
#include <atomic>
#include <csignal>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "device/cluster.h"
#include "device/device.h"
#include "integrators/default_integrator.h"
#include "integrators/integrator_table.h"
#include "io/image_io.h"
#include "render/option_table.h"
#include "render/render_job.h"
#include "render/render_loop.h"
#include "render/standard_observers.h"
#include "util/cancellation.h"
#include "util/error.h"
#include "util/version.h"

namespace py = pybind11;

namespace clppm {
namespace {

volatile std::sig_atomic_t g_sigint = 0;

extern "C" void on_sigint(int) {
    g_sigint = 1;
    request_cancel(); // the pass in progress stops at its next batch
}

// While a long call runs without the GIL: SIGINT becomes a stop request instead of Python's flag,
// which nobody would look at until the call returned. Only in the main thread, where Python
// handles signals; elsewhere Python's handler stays.
class InterruptScope {
public:
    InterruptScope() {
        const py::module_ threading = py::module_::import("threading");
        installed_ = threading.attr("current_thread")().is(threading.attr("main_thread")());
        if (!installed_) return;
        g_sigint = 0;
        struct sigaction sa {};
        sa.sa_handler = on_sigint;
        sigemptyset(&sa.sa_mask);
        sa.sa_flags = SA_RESTART;
        sigaction(SIGINT, &sa, &previous_);
    }
    ~InterruptScope() {
        if (installed_) sigaction(SIGINT, &previous_, nullptr);
    }
    InterruptScope(const InterruptScope&) = delete;
    InterruptScope& operator=(const InterruptScope&) = delete;
    bool interrupted() const { return installed_ && g_sigint != 0; }

private:
    bool installed_ = false;
    struct sigaction previous_ {};
};

py::array_t<float> to_numpy(Image img) {
    auto* rgb = new std::vector<float>(std::move(img.rgb));
    py::capsule owner(rgb, [](void* p) { delete static_cast<std::vector<float>*>(p); });
    return py::array_t<float>({py::ssize_t(img.height), py::ssize_t(img.width), py::ssize_t(3)}, rgb->data(), owner);
}

py::array_t<float> plane_to_numpy(const std::vector<float>& v, int width, int height) {
    py::array_t<float> a({py::ssize_t(height), py::ssize_t(width)});
    std::copy(v.begin(), v.end(), a.mutable_data());
    return a;
}

py::object json_to_python(const Json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

RenderOptions options_from(const std::optional<std::string>& scene,
                           const std::vector<std::pair<std::string, std::string>>& args) {
    RenderOptions o;
    if (scene) set_scene(o, *scene);
    for (const auto& [name, value] : args) {
        const RenderOptionSpec* spec = find_render_option(name);
        if (!spec) throw Error("unknown option " + name);
        apply_render_option(o, *spec, name, value);
    }
    check_render_options(o);
    return o;
}

// A render set up and stepped from Python: RenderJob and RenderLoop with the standard observers.
class Renderer {
public:
    Renderer(const std::optional<std::string>& scene, const std::vector<std::pair<std::string, std::string>>& args) {
        const RenderOptions options = options_from(scene, args);
        log_ = std::make_unique<RenderLog>(options.quiet);
        InterruptScope scope;
        {
            py::gil_scoped_release release;
            auto observers = standard_observers(options, *log_);
            job_ = std::make_unique<RenderJob>(options, *log_);
            loop_ = std::make_unique<RenderLoop>(*job_, std::move(observers));
        }
        if (scope.interrupted()) { // during the set-up (the kernel build, say): there is no render yet
            clear_cancel();
            PyErr_SetNone(PyExc_KeyboardInterrupt);
            throw py::error_already_set();
        }
    }

    // One pass whatever the stop policy says; False when interrupted.
    bool run_pass() {
        return stepped([this] { return loop_->run_pass(); });
    }

    // The stop policy, then a pass: True when a pass ran, False when the policy stops the render
    // (interrupted() says whether a stop request did).
    bool step() {
        return stepped([this] { return loop_->step(); });
    }

    // The same for as many passes as the integrator takes to a launch (the path tracer's short
    // passes, several to a launch), never past the pass limit or a pass the outputs count.
    bool step_batch() {
        return stepped([this] { return loop_->step_batch(); });
    }

    // Passes until the policy stops them, then the end (outputs written as the options say).
    bool render() {
        const bool whole = stepped([this] {
            while (loop_->step_batch()) {}
            return !loop_->interrupted();
        });
        finish();
        return whole;
    }

    py::dict finish() {
        need_open();
        RenderEnd end;
        {
            py::gil_scoped_release release;
            end = loop_->finish();
        }
        finished_ = true;
        py::dict d;
        d["interrupted"] = end.interrupted;
        d["stopped_by_viewer"] = end.stopped_by_viewer;
        d["render_seconds"] = end.render_seconds;
        d["nothing_written"] = end.nothing_written;
        d["defective_pixels"] = end.defective_pixels;
        return d;
    }

    void close() {
        if (!job_) return;
        if (!finished_) finish();
        loop_.reset();
        job_.reset();
    }

    // From another thread (a GUI's Cancel button): the pass in flight stops at its next batch and
    // its call returns False, as after Ctrl-C; between the calls of an iteration, the next call
    // does. This render's alone: other renders in the process go on.
    void cancel() { token_.request(); }
    // A run_pass(), an iteration or a render() begins (python/clppm/__init__.py): a cancel from
    // before it was meant for nothing, and is dropped.
    void begin() { token_.clear(); }
    bool interrupted() const { return signalled_ || cancelled_ || (loop_ && loop_->interrupted()); }
    void clear_interrupt() {
        clear_cancel();
        signalled_ = cancelled_ = false;
        if (loop_) loop_->clear_interrupt();
    }

    py::array_t<float> image() {
        need_job();
        Image img;
        {
            py::gil_scoped_release release;
            img = job_->image(interrupted());
        }
        return to_numpy(std::move(img));
    }

    py::object error_estimate() {
        need_job();
        if (!job_->estimating()) return py::none();
        const ErrorImage& e = job_->error();
        py::dict d;
        d["estimated"] = e.expected_error;
        d["bound"] = e.image_error;
        d["target"] = job_->options().target_error;
        d["reached"] = job_->error_target_reached();
        d["passes"] = e.passes;
        d["relative"] = plane_to_numpy(e.relative, e.width, e.height);
        return std::move(d);
    }

    py::object stats() {
        need_job();
        RenderEnd end;
        end.interrupted = interrupted();
        end.render_seconds = job_->render_seconds();
        return json_to_python(job_->stats_json(end));
    }

    void save(const std::string& path) {
        need_job();
        RenderOptions o;
        const RenderOptionSpec* spec = find_render_option("--output");
        apply_render_option(o, *spec, "save", path); // the same check as --output: an .exr name
        py::gil_scoped_release release;
        job_->save_images(path, job_->options().write_png, interrupted());
    }

    uint64_t passes() const {
        need_job();
        return job_->passes();
    }
    uint64_t pass_limit() const {
        need_job();
        return job_->pass_limit();
    }
    std::vector<std::string> warnings() const { return log_ ? log_->warnings() : std::vector<std::string>{}; }
    // What is rendered: every option that shapes the image or says when the render stops, by its
    // flag ("--alpha"), as the option table reads it back (the values every MPI process shares), with
    // the integrator the scene got; and the scene, the output and the resolved limits. The package
    // (python/clppm/__init__.py) gives the flags their keyword names.
    py::object settings() const {
        need_job();
        const RenderOptions& o = job_->options();
        Json d = options_every_rank_shares(o);
        d.erase("SCENE");
        d["scene"] = o.scene;
        d["output"] = o.output;
        d["pass_limit"] = job_->pass_limit();
        d["time_limit"] = o.time_limit;
        return json_to_python(d);
    }

private:
    template <class F>
    bool stepped(F f) {
        need_open();
        InterruptScope scope;
        bool ok;
        {
            py::gil_scoped_release release;
            const CancelScope cancel(&token_);
            ok = f();
        }
        cancelled_ = !ok && token_.requested(); // one that came after the last batch was too late
        // Ctrl-C during a pass that completed anyway (it came after its last photon batch): the
        // pass is kept, and the call still answers the interrupt.
        signalled_ = signalled_ || scope.interrupted();
        return ok && !scope.interrupted();
    }
    void need_job() const {
        if (!job_) throw Error("this Renderer is closed");
    }
    void need_open() const {
        need_job();
        if (finished_) throw Error("this Renderer has finished its render (render() or close()): make a new one");
    }

    std::unique_ptr<RenderLog> log_;
    std::unique_ptr<RenderJob> job_;
    std::unique_ptr<RenderLoop> loop_;
    bool finished_ = false;
    bool signalled_ = false; // a SIGINT during the last call
    bool cancelled_ = false; // cancel() came during the last call
    CancelToken token_;      // cancel()'s request, which the passes of a call see
};

py::object device_list() {
    Json out = Json::array();
    for (const DeviceInfo& d : list_devices())
        out.push_back({{"index", d.index},
                       {"name", d.name},
                       {"platform", d.platform_name},
                       {"implementation", d.implementation()},
                       {"type", d.type_name()},
                       {"driver", d.driver_version},
                       {"compute_units", d.compute_units},
                       {"global_memory", d.global_mem},
                       {"fp64", d.fp64}});
    return json_to_python(out);
}

py::object option_list() {
    auto text = [](const char* s) { return s ? Json(s) : Json(); };
    Json out = Json::array();
    for (const RenderOptionSpec& s : render_option_table())
        out.push_back({{"name", s.name},
                       {"group", s.group},
                       {"flag", s.metavar == nullptr},
                       {"metavar", text(s.metavar)},
                       {"help", s.help},
                       {"range", text(s.range)},
                       {"default", text(s.default_text)},
                       {"role", s.role == OptionRole::Image ? "image"
                                : s.role == OptionRole::Run ? "run"
                                                            : "local"}});
    return json_to_python(out);
}

// The integrators as the table lists them, "auto" first with its rule (--integrator's help).
py::object integrator_list() {
    Json out = Json::array();
    out.push_back({{"name", "auto"},
                   {"alias", Json()},
                   {"summary", std::string("the fastest for the scene (") + kDefaultIntegratorRule + ")"}});
    for (const IntegratorRow& row : integrator_table())
        out.push_back({{"name", row.name}, {"alias", row.alias ? Json(row.alias) : Json()}, {"summary", row.summary}});
    return json_to_python(out);
}

std::unique_ptr<ClusterSession> g_mpi;

} // namespace
} // namespace clppm

PYBIND11_MODULE(_clppm, m) {
    using namespace clppm;
    m.doc() = "clppm's native module; use the clppm package (python/clppm/__init__.py).";
    static py::exception<Error> error(m, "Error");
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const Error& e) {
            PyErr_SetString(error.ptr(), e.what());
        } catch (const cl::Error& e) {
            const std::string msg =
                std::string("OpenCL call ") + e.what() + " failed with code " + std::to_string(e.err());
            PyErr_SetString(error.ptr(), msg.c_str());
        } catch (const PassCancelled&) {
            PyErr_SetNone(PyExc_KeyboardInterrupt);
        }
    });
    // Started by an MPI launcher (mpirun -np N python script.py): every process renders its share
    // of each pass, as the command line's do; MPI ends with the interpreter.
    if (launcher_process_count([](const char* name) -> const char* { return std::getenv(name); }) > 0) {
        g_mpi = std::make_unique<ClusterSession>(nullptr, nullptr);
        py::module_::import("atexit").attr("register")(py::cpp_function([] { g_mpi.reset(); }));
    }
    // pybind11 (2.10) looks numpy's C API up once, under a static's guard, by importing numpy: in a
    // thread that import lets other threads run, and one holding the GIL and waiting on the guard
    // then deadlocks with it (four threads rendering at once hung). Looked up here, at import.
    (void)py::dtype::of<float>();
    m.attr("__version__") = kVersion;
    m.attr("mpi_rank") = cluster().rank();
    m.attr("mpi_size") = cluster().size();
    m.def("devices", &device_list, "The OpenCL devices, as --list-devices lists them.");
    m.def("option_table", &option_list, "The render options: name, flag, range, default, help, group, role.");
    m.def("integrators", &integrator_list, "The integrators: name, alias, summary; auto first.");
    m.def(
        "read_exr",
        [](const std::string& path) {
            Image img;
            {
                py::gil_scoped_release release;
                img = read_exr(path);
            }
            return to_numpy(std::move(img));
        },
        py::arg("path"), "The R, G, B of an OpenEXR file as float32 (height, width, 3).");
    py::class_<Renderer>(m, "Renderer")
        .def(py::init<const std::optional<std::string>&, const std::vector<std::pair<std::string, std::string>>&>(),
             py::arg("scene"), py::arg("args"))
        .def("run_pass", &Renderer::run_pass)
        .def("step", &Renderer::step)
        .def("step_batch", &Renderer::step_batch)
        .def("render", &Renderer::render)
        .def("finish", &Renderer::finish)
        .def("close", &Renderer::close)
        .def("cancel", &Renderer::cancel)
        .def("begin", &Renderer::begin)
        .def("interrupted", &Renderer::interrupted)
        .def("clear_interrupt", &Renderer::clear_interrupt)
        .def("image", &Renderer::image)
        .def("error_estimate", &Renderer::error_estimate)
        .def("stats", &Renderer::stats)
        .def("save", &Renderer::save, py::arg("path"))
        .def_property_readonly("passes", &Renderer::passes)
        .def_property_readonly("pass_limit", &Renderer::pass_limit)
        .def_property_readonly("warnings", &Renderer::warnings)
        .def_property_readonly("settings", &Renderer::settings);
}

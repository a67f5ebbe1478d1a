#include "cli/options.h"

#include <algorithm>
#include <map>
#include <memory>

#include <CLI/CLI.hpp>

#include "cli/help_formatter.h"
#include "render/option_table.h"
#include "util/error.h"

namespace clppm {
namespace {

// The command line's own flags, beside the render options.
struct CliFlag {
    const char* group;
    const char* name;
    const char* short_name;
    const char* help;
    bool CommandLine::*field;
};

const CliFlag kCliFlags[] = {
    {"Devices and kernels", "--list-devices", nullptr, "List the OpenCL devices and exit", &CommandLine::list_devices},
    {"Other", "--help", "-h", "Print this help and exit", &CommandLine::help},
    {"Other", "--version", nullptr, "Print the version and exit", &CommandLine::version},
};

// One name of either table: the render option's spec, or the flag.
struct Named {
    const RenderOptionSpec* spec = nullptr;
    const CliFlag* flag = nullptr;
    const char* name() const { return spec ? spec->name : flag->name; }
    const char* metavar() const { return spec ? spec->metavar : nullptr; }
    explicit operator bool() const { return spec || flag; }
};

Named find_option(const std::string& name) {
    if (const RenderOptionSpec* spec = find_render_option(name)) return {spec, nullptr};
    for (const CliFlag& f : kCliFlags)
        if (name == f.name || (f.short_name && name == f.short_name)) return {nullptr, &f};
    return {};
}

struct ParseState {
    CommandLine command;
    std::map<const RenderOptionSpec*, std::string> shown; // the spelling typed last ("-o" or "--output"), for messages
};

// Levenshtein distance, for suggestions.
size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = up;
        }
    }
    return row[b.size()];
}

// "unknown option --pases (did you mean --passes? see --help)": the nearest long name within a
// third of its length in edits (at least 1, at most 3), else no suggestion.
[[noreturn]] void unknown_option(const std::string& name) {
    std::vector<const char*> names;
    for (const RenderOptionSpec& spec : render_option_table()) names.push_back(spec.name);
    for (const CliFlag& f : kCliFlags) names.push_back(f.name);
    const char* best = nullptr;
    size_t best_distance = 0;
    for (const char* n : names) {
        const size_t d = edit_distance(name, n);
        if (!best || d < best_distance) best = n, best_distance = d;
    }
    const size_t allowed = std::clamp<size_t>(std::string(best).size() / 3, 1, 3);
    if (name.rfind("--", 0) == 0 && best_distance <= allowed)
        throw Error("unknown option " + name + " (did you mean " + best + "? see --help)");
    throw Error("unknown option " + name + " (see --help)");
}

// Whether a token is itself an option (so it cannot be the previous option's value): "--name" or
// "--name=..." or "-o" with a known name. Negative numbers are values.
bool is_option_token(const std::string& token) {
    if (token.rfind("--", 0) == 0) return bool(find_option(token.substr(0, token.find('='))));
    return token.size() >= 2 && token[0] == '-' && find_option(token.substr(0, 2)) &&
           (token.size() == 2 || token[2] == '=');
}

constexpr size_t kHelpColumn = 30, kHelpWidth = 100;

// The environment variables clppm reads, for the end of --help.
std::string environment_help() {
    const char* env[][2] = {
        {"CLPPM_KERNEL_DIR", "load the kernel sources from this folder instead of the embedded copies"},
        {"CLPPM_CACHE_DIR", "where built programs are cached (else $XDG_CACHE_HOME/clppm, else ~/.cache/clppm; not for "
                            "PoCL, which keeps its own)"},
        {"CLPPM_NO_CACHE", "1: build the kernels every time, cache nothing"},
        {"CLPPM_BUILD_LOG", "1: print the compiler's log of successful kernel builds"},
        {"CLPPM_LOCAL_SIZE", "force this work-group size (the image does not change)"},
        {"CLPPM_PHOTON_BATCH", "trace each pass's photons in batches of at most this many (the image does not change)"},
        {"CLPPM_PASS_BATCH",
         "the path tracer: run at most this many passes a launch (1: one; the image does not change)"},
        {"CLPPM_OCLGRIND", "1: handle device buffers as oclgrind's check for uninitialised values needs (host "
                           "writes for fills, no buffer released before exit; the image does not change)"},
        {"POCL_DEVICES", "PoCL's devices, e.g. \"pthread pthread\" for two CPU devices (--device all)"}};
    std::string out = "Environment:\n";
    for (const auto& [name, what] : env) {
        std::string line = std::string("  ") + name;
        line += std::string(kHelpColumn > line.size() ? kHelpColumn - line.size() : 1, ' ');
        std::string text = wrapped(what, kHelpWidth - kHelpColumn);
        for (size_t p = text.find('\n'); p != std::string::npos; p = text.find('\n', p + 1))
            text.insert(p + 1, std::string(kHelpColumn, ' '));
        out += line + text + "\n";
    }
    return out;
}

// The description column of an option: its help, range and default, wrapped.
std::string option_description(const RenderOptionSpec& spec) {
    std::string text = spec.help;
    if (spec.range && spec.metavar) text += std::string(". Must be ") + spec.range;
    if (spec.default_text) text += std::string(". Default: ") + spec.default_text;
    return wrapped(text + ".", kHelpWidth - kHelpColumn - 2);
}

// The command line as a CLI11 App over `st`: one option per table entry, its callback the entry's
// apply, run as each occurrence is parsed (so, left to right, the last one winning and --device
// collecting every one); the scene files as a positional; render and compare as subcommands
// (render is the default; compare has its own parser, compare_command).
std::unique_ptr<CLI::App> make_app(ParseState& st, std::vector<std::string>& scenes) {
    auto app = std::make_unique<CLI::App>(
        "Renders SCENE (default: the built-in Cornell box) with progressive photon mapping in OpenCL.\n"
        "Values may be given as --opt VALUE or --opt=VALUE (-o FILE or -o=FILE); choices ignore case.",
        "clppm");
    app->set_help_flag(); // --help is a flag of ours: it stops parsing, as --version does
    app->formatter(
        std::make_shared<HelpFormatter>("Usage: clppm [render] [options] [SCENE.gltf|SCENE.glb]\n"
                                        "       clppm compare IMAGE.exr REFERENCE.exr [--diff OUT.png] [--box K]\n",
                                        kHelpColumn));
    app->add_subcommand("render", "Render a scene (the default: `clppm [options] SCENE` is the same)");
    app->add_subcommand("compare", "How far an image is from a reference, as JSON (clppm compare --help)");
    app->add_option("SCENE", scenes, "A .gltf or .glb file; none renders the built-in Cornell box")
        ->group("Scene")
        ->type_name("");
    // The flags go into their groups: a group's options keep the order they are added in.
    auto add_flags = [&](const char* group) {
        for (const CliFlag& f : kCliFlags) {
            if (std::string(f.group) != group) continue;
            const std::string names = f.short_name ? std::string(f.short_name) + "," + f.name : f.name;
            app->add_flag_function(
                   names, [&st, &f](int64_t) { st.command.*(f.field) = true; },
                   wrapped(std::string(f.help) + ".", kHelpWidth - kHelpColumn - 2))
                ->group(f.group);
        }
    };
    for (const RenderOptionSpec& spec : render_option_table()) {
        if (std::string(spec.group) == "Devices and kernels" && std::string(spec.name) == "--device")
            add_flags("Devices and kernels"); // --list-devices first
        const std::string names = spec.short_name ? std::string(spec.short_name) + "," + spec.name : spec.name;
        st.shown.emplace(&spec, spec.name);
        const std::string& typed = st.shown.at(&spec); // map nodes stay put
        CLI::Option* opt;
        if (spec.metavar) {
            opt = app->add_option_function<std::string>(
                names,
                [&st, &spec, &typed](const std::string& v) { apply_render_option(st.command.render, spec, typed, v); },
                option_description(spec));
            opt->type_name(spec.metavar);
        } else {
            opt = app->add_flag_function(
                names, [&st, &spec, &typed](int64_t) { apply_render_option(st.command.render, spec, typed, ""); },
                option_description(spec));
        }
        opt->group(spec.group)->trigger_on_parse()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    }
    add_flags("Other");
    app->footer(environment_help());
    return app;
}

// What CLI11 leaves to us, checked before it parses, left to right, so that the messages are
// clppm's: an unknown option (with a suggestion), a flag given a value, a missing value (an
// option where the value should be is not taken as the value: "--passes --quiet"), and -h,
// --help or --version, which end the parse (what follows is not looked at). The result is the
// arguments in one canonical form for CLI11: "--name VALUE" or "--flag", the scene files last
// after "--" (so no file name is taken for an option or a subcommand).
std::vector<std::string> canonical_arguments(ParseState& st, const std::vector<std::string>& args) {
    std::vector<std::string> out, scenes;
    bool options_ended = false; // after "--" everything is a scene file
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        if (!options_ended && arg == "--") {
            options_ended = true;
            continue;
        }
        if (options_ended || arg.size() < 2 || arg[0] != '-') {
            scenes.push_back(arg);
            continue;
        }
        // "--name=value", and "-o=value" for the short forms.
        const size_t eq =
            arg.rfind("--", 0) == 0 ? arg.find('=') : (arg.size() > 2 && arg[2] == '=' ? 2 : std::string::npos);
        const std::string name = arg.substr(0, eq);
        const Named found = find_option(name);
        if (!found) unknown_option(name);
        if (found.flag && found.flag->field != &CommandLine::list_devices) { // --help, --version
            if (eq != std::string::npos) throw Error(name + " takes no value");
            st.command.*(found.flag->field) = true;
            break;
        }
        out.push_back(found.name());
        if (!found.metavar()) {
            if (eq != std::string::npos) throw Error(name + " takes no value");
        } else if (eq != std::string::npos) {
            out.push_back(arg.substr(eq + 1));
        } else if (i + 1 < args.size() && !is_option_token(args[i + 1])) {
            out.push_back(args[++i]);
        } else {
            throw Error(name + ": missing value " + found.spec->metavar + " (must be " + found.spec->range + ")");
        }
        // The spelling the messages name; CLI11 applies the occurrences in order, so the
        // spelling of each would need a token of its own: the last one typed is a fair name.
        if (found.spec) st.shown[found.spec] = name;
    }
    out.push_back("--");
    out.insert(out.end(), scenes.begin(), scenes.end());
    return out;
}

} // namespace

CommandLine parse_options(const std::vector<std::string>& given) {
    std::vector<std::string> args = given;
    if (!args.empty() && args[0] == "render") args.erase(args.begin()); // `clppm render ...` = `clppm ...`
    ParseState st;
    st.command.render.output = "clppm.exr"; // the command line always writes an image
    std::vector<std::string> scenes;
    std::unique_ptr<CLI::App> app = make_app(st, scenes);
    std::vector<std::string> tokens = canonical_arguments(st, args);
    std::reverse(tokens.begin(), tokens.end()); // CLI11 takes a vector last argument first
    try {
        app->parse(tokens);
    } catch (const CLI::ParseError& e) {
        // canonical_arguments leaves CLI11 nothing to refuse; should it, the message is one line.
        throw Error(std::string("command line: ") + e.what());
    }
    for (const std::string& scene : scenes) set_scene(st.command.render, scene);
    if (st.command.help || st.command.version) return st.command;
    check_render_options(st.command.render);
    return st.command;
}

CommandLine parse_options(int argc, char** argv) {
    std::vector<std::string> args;
    for (int i = 1; i < argc; ++i) args.emplace_back(argv[i]);
    return parse_options(args);
}

std::string usage() {
    ParseState st;
    std::vector<std::string> scenes;
    return make_app(st, scenes)->help();
}

} // namespace clppm

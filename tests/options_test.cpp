// options: every option in both spellings, the defaults, and the exact one-line errors.
#include "cli/options.h"

#include <gtest/gtest.h>

#include <sstream>

#include "integrators/integrator_table.h"
#include "util/error.h"

namespace clppm {
namespace {

using Args = std::vector<std::string>;

std::string error_of(const Args& args) {
    try {
        parse_options(args);
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

// The defaults --help states as plain values are checked against the table in
// tests/option_roles_test.cpp (HelpsDefaultIsTheValueWhenNotGiven); these are the rest.
TEST(Options, Defaults) {
    CommandLine o = parse_options(Args{});
    EXPECT_EQ(o.render.scene, "");
    EXPECT_EQ(o.render.output, "clppm.exr");
    EXPECT_TRUE(o.render.write_png);
    EXPECT_EQ(o.render.settings.width, 0);
    EXPECT_EQ(o.render.settings.height, 0);
    EXPECT_FALSE(o.render.passes.has_value());
    EXPECT_EQ(pass_limit(o.render, 64), 64u); // the integrator's default, without --time
    EXPECT_EQ(o.render.time_limit, 0.0);
    EXPECT_EQ(o.render.settings.radius, 0.0);
    EXPECT_FALSE(o.list_devices);
    EXPECT_TRUE(o.render.devices.empty());
    EXPECT_FALSE(o.render.quiet);
    EXPECT_EQ(o.render.stats_json, "");
    EXPECT_EQ(o.render.progressive_output, 0u);
    EXPECT_EQ(o.render.kernel_dir, "");
    EXPECT_EQ(o.render.dump_kernel_source, "");
    EXPECT_FALSE(o.help);
    EXPECT_FALSE(o.version);
    EXPECT_EQ(o.render.tone.curve, ToneCurve::Aces);
    EXPECT_EQ(o.render.tone.exposure_ev, 0.0);
    EXPECT_FALSE(o.render.tone.auto_exposure);
}

// Choices are case-insensitive; the PNG's tone options and their ranges.
TEST(Options, ChoicesIgnoreCaseAndToneOptions) {
    CommandLine o = parse_options(Args{"--integrator", "SPPM", "--direct", "Photons", "--filter", "TENT", "--tonemap",
                                       "Clip", "--exposure=-2.5", "--auto-exposure", "--sampler", "Independent"});
    EXPECT_EQ(o.render.settings.sampler, Sampler::Independent);
    EXPECT_EQ(parse_options(Args{}).render.settings.sampler, Sampler::Sobol);
    EXPECT_EQ(o.render.settings.integrator, "sppm");
    EXPECT_NE(o.render.settings.integrator, "auto");
    EXPECT_EQ(parse_options(Args{"--integrator", "ppm", "--integrator=Auto"}).render.settings.integrator, "auto");
    EXPECT_TRUE(parse_options(Args{"--passes", "64"}).render.passes.has_value());
    EXPECT_EQ(pass_limit(parse_options(Args{"--time", "5"}).render, 64), 0u);
    EXPECT_EQ(o.render.settings.direct, DirectLighting::Photons);
    EXPECT_EQ(o.render.settings.filter, PixelFilter::Tent);
    EXPECT_EQ(o.render.tone.curve, ToneCurve::Clip);
    EXPECT_EQ(o.render.tone.exposure_ev, -2.5);
    EXPECT_TRUE(o.render.tone.auto_exposure);
    EXPECT_EQ(error_of({"--tonemap", "agx"}), "--tonemap agx: must be clip, aces or reinhard");
    EXPECT_EQ(error_of({"--exposure", "65"}), "--exposure 65: must be a number in -64..64");
    EXPECT_EQ(error_of({"--exposure", "nan"}), "--exposure nan: must be a number in -64..64");
}

// Every valued option, once as "--opt value" and once as "--opt=value".
class BothForms : public ::testing::TestWithParam<bool> {
protected:
    CommandLine parse(const Args& pairs) {
        Args args;
        for (size_t i = 0; i + 1 < pairs.size(); i += 2) {
            if (GetParam()) {
                args.push_back(pairs[i] + "=" + pairs[i + 1]);
            } else {
                args.push_back(pairs[i]);
                args.push_back(pairs[i + 1]);
            }
        }
        return parse_options(args);
    }
};

TEST_P(BothForms, EveryValuedOption) {
    CommandLine o = parse({"--output",
                           "r/x.exr",
                           "--width",
                           "640",
                           "--height",
                           "480",
                           "--passes",
                           "10",
                           "--time",
                           "2.5",
                           "--photons",
                           "1000",
                           "--alpha",
                           "0.5",
                           "--radius",
                           "0.25",
                           "--seed",
                           "18446744073709551615",
                           "--device",
                           "gpu",
                           "--device",
                           "1",
                           "--camera",
                           "2",
                           "--stats-json",
                           "s.json",
                           "--integrator",
                           "pt",
                           "--direct",
                           "photons",
                           "--spp",
                           "256",
                           "--max-bounces",
                           "1024",
                           "--progressive-output",
                           "8",
                           "--kernel-dir",
                           "kernels",
                           "--dump-kernel-source",
                           "k.cl"});
    EXPECT_EQ(o.render.output, "r/x.exr");
    EXPECT_EQ(o.render.settings.width, 640);
    EXPECT_EQ(o.render.settings.height, 480);
    EXPECT_EQ(o.render.passes, 10u);
    EXPECT_EQ(o.render.time_limit, 2.5);
    EXPECT_EQ(o.render.settings.photons, 1000u);
    EXPECT_EQ(o.render.settings.alpha, 0.5);
    EXPECT_EQ(o.render.settings.radius, 0.25);
    EXPECT_EQ(o.render.settings.seed, UINT64_MAX);
    EXPECT_EQ(o.render.devices, (std::vector<std::string>{"gpu", "1"}));
    EXPECT_EQ(o.render.settings.camera, 2);
    EXPECT_EQ(o.render.stats_json, "s.json");
    EXPECT_EQ(o.render.settings.integrator, "pt");
    EXPECT_EQ(o.render.settings.direct, DirectLighting::Photons);
    EXPECT_EQ(o.render.settings.spp, 256);
    EXPECT_EQ(o.render.settings.max_bounces, 1024);
    EXPECT_EQ(o.render.progressive_output, 8u);
    EXPECT_EQ(o.render.kernel_dir, "kernels");
    EXPECT_EQ(o.render.dump_kernel_source, "k.cl");
}

TEST_P(BothForms, RangeEnds) {
    CommandLine o = parse({"--width", "16384", "--height", "1", "--photons", "2147483647", "--alpha", "1", "--seed",
                           "0", "--integrator", "ppm", "--direct", "sample", "--spp", "1", "--max-bounces", "1"});
    EXPECT_EQ(o.render.settings.width, 16384);
    EXPECT_EQ(o.render.settings.height, 1);
    EXPECT_EQ(o.render.settings.photons, 2147483647u);
    EXPECT_EQ(o.render.settings.alpha, 1.0);
    EXPECT_EQ(o.render.settings.seed, 0u);
    EXPECT_EQ(o.render.settings.integrator, "ppm");
    EXPECT_NE(o.render.settings.integrator, "auto");
    EXPECT_EQ(o.render.settings.direct, DirectLighting::Sample);
    EXPECT_EQ(o.render.settings.spp, 1);
    EXPECT_EQ(o.render.settings.max_bounces, 1);
}

TEST_P(BothForms, DistributedEffectOptions) {
    CommandLine o =
        parse({"--integrator", "sppm", "--filter", "tent", "--aperture", "0.05", "--focus-distance", "3.5"});
    EXPECT_EQ(o.render.settings.integrator, "sppm");
    EXPECT_EQ(o.render.settings.filter, PixelFilter::Tent);
    EXPECT_EQ(o.render.settings.aperture, 0.05);
    EXPECT_EQ(o.render.settings.focus_distance, 3.5);
    EXPECT_EQ(parse({"--integrator", "pppm"}).render.settings.integrator, "pppm");
    CommandLine d = parse({});
    EXPECT_EQ(d.render.settings.filter, PixelFilter::Box);
    EXPECT_LT(d.render.settings.aperture, 0.0); // the camera's own
    EXPECT_EQ(d.render.settings.focus_distance, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Options, BothForms, ::testing::Values(false, true),
                         [](const auto& p) { return p.param ? "Equals" : "Separate"; });

TEST(Options, FlagsAndShortForms) {
    CommandLine o = parse_options(Args{"-o", "a.exr", "--no-png", "--list-devices", "--quiet", "scene.glb"});
    EXPECT_EQ(o.render.output, "a.exr");
    EXPECT_FALSE(o.render.write_png);
    EXPECT_TRUE(o.list_devices);
    EXPECT_TRUE(o.render.quiet);
    EXPECT_EQ(o.render.scene, "scene.glb");
    EXPECT_TRUE(parse_options(Args{"-h"}).help);
    EXPECT_TRUE(parse_options(Args{"--help", "--bogus"}).help); // help wins over what follows
    EXPECT_TRUE(parse_options(Args{"--version"}).version);
}

TEST(Options, ScenePositional) {
    EXPECT_EQ(parse_options(Args{"a/b/Box.GLTF"}).render.scene, "a/b/Box.GLTF");
    EXPECT_EQ(parse_options(Args{"--passes", "3", "x.gltf", "--quiet"}).render.scene, "x.gltf");
    EXPECT_EQ(parse_options(Args{"--", "-odd.gltf"}).render.scene, "-odd.gltf");
    EXPECT_EQ(error_of({"a.gltf", "b.glb"}), "unexpected second scene file b.glb (already given a.gltf)");
    EXPECT_EQ(error_of({"scene.obj"}), "scene file scene.obj: must be a .gltf or .glb file");
    EXPECT_EQ(error_of({"gltf"}), "scene file gltf: must be a .gltf or .glb file");
}

TEST(Options, PassesAndTime) {
    EXPECT_EQ(pass_limit(parse_options(Args{"--time", "10"}).render, 64), 0u); // unlimited, the time bounds it
    CommandLine o = parse_options(Args{"--time", "10", "--passes", "5"});
    EXPECT_EQ(o.render.passes, 5u);
    EXPECT_EQ(o.render.time_limit, 10.0);
    o = parse_options(Args{"--passes", "0", "--time", "0.5"});
    EXPECT_EQ(o.render.passes, 0u);
    EXPECT_EQ(o.render.time_limit, 0.5);
    EXPECT_EQ(error_of({"--passes", "0"}), "--passes 0: unlimited passes need --time");
}

TEST(Options, UnknownMissingAndStrayValues) {
    EXPECT_EQ(error_of({"--foo"}), "unknown option --foo (see --help)");
    // A near miss gets a suggestion.
    EXPECT_EQ(error_of({"--pases", "3"}), "unknown option --pases (did you mean --passes? see --help)");
    EXPECT_EQ(error_of({"--integrater=sppm"}), "unknown option --integrater (did you mean --integrator? see --help)");
    EXPECT_EQ(error_of({"--env-colour", "1,1,1"}),
              "unknown option --env-colour (did you mean --env-color? see --help)");
    // An option where a value should be is a missing value, not the value ("--passes --quiet"
    // took "--quiet" as the number); negative numbers are values.
    EXPECT_EQ(error_of({"--passes", "--quiet"}),
              "--passes: missing value N (must be an integer >= 1 (0 = unlimited, with --time))");
    EXPECT_EQ(error_of({"-o", "--width=3"}), "-o: missing value FILE (must be a file name ending in .exr)");
    EXPECT_EQ(parse_options(Args{"--exposure", "-2"}).render.tone.exposure_ev, -2.0);
    // The short form takes "=" too, as the long ones do.
    EXPECT_EQ(parse_options(Args{"-o=x.exr"}).render.output, "x.exr");
    EXPECT_EQ(error_of({"--foo=3"}), "unknown option --foo (see --help)");
    EXPECT_EQ(error_of({"-x"}), "unknown option -x (see --help)");
    EXPECT_EQ(error_of({"--alpha"}), "--alpha: missing value A (must be in (0, 1])");
    EXPECT_EQ(error_of({"-o"}), "-o: missing value FILE (must be a file name ending in .exr)");
    EXPECT_EQ(error_of({"--quiet=yes"}), "--quiet takes no value");
}

struct BadValue {
    Args args;
    std::string message;
};

class BadValues : public ::testing::TestWithParam<BadValue> {};

TEST_P(BadValues, NameTheOptionAndRange) { EXPECT_EQ(error_of(GetParam().args), GetParam().message); }

const std::string kSize = ": must be an integer in 1..16384";

INSTANTIATE_TEST_SUITE_P(
    Options, BadValues,
    ::testing::Values(
        BadValue{{"--output", "x.png"}, "--output x.png: must be a file name ending in .exr"},
        BadValue{{"-o", ".exr"}, "-o .exr: must be a file name ending in .exr"},
        BadValue{{"--width", "16385"}, "--width 16385" + kSize}, BadValue{{"--width", "-1"}, "--width -1" + kSize},
        // 0 is no size: leaving the option out takes the camera's.
        BadValue{{"--width", "0"}, "--width 0" + kSize}, BadValue{{"--height", "0"}, "--height 0" + kSize},
        BadValue{{"--width", "12.5"}, "--width 12.5" + kSize}, BadValue{{"--height=abc"}, "--height abc" + kSize},
        BadValue{{"--height="}, "--height ''" + kSize},
        BadValue{{"--passes", "-3"}, "--passes -3: must be an integer >= 1 (0 = unlimited, with --time)"},
        BadValue{{"--passes", "99999999999999999999"},
                 "--passes 99999999999999999999: must be an integer >= 1 (0 = unlimited, with --time)"},
        BadValue{{"--time", "0"}, "--time 0: must be a number of seconds > 0"},
        BadValue{{"--time", "inf"}, "--time inf: must be a number of seconds > 0"},
        BadValue{{"--time", "1s"}, "--time 1s: must be a number of seconds > 0"},
        BadValue{{"--photons", "0"}, "--photons 0: must be an integer in 1..2147483647"},
        BadValue{{"--photons", "2147483648"}, "--photons 2147483648: must be an integer in 1..2147483647"},
        BadValue{{"--alpha", "1.5"}, "--alpha 1.5: must be in (0, 1]"},
        BadValue{{"--alpha", "0"}, "--alpha 0: must be in (0, 1]"},
        BadValue{{"--alpha", "nan"}, "--alpha nan: must be in (0, 1]"},
        BadValue{{"--radius", "-0.1"}, "--radius -0.1: must be a finite number > 0"},
        BadValue{{"--radius", "0"}, "--radius 0: must be a finite number > 0"},
        BadValue{{"--radius", "1e999"}, "--radius 1e999: must be a finite number > 0"},
        BadValue{{"--seed", "-1"}, "--seed -1: must be an integer in 0..18446744073709551615"},
        BadValue{{"--seed", "18446744073709551616"},
                 "--seed 18446744073709551616: must be an integer in 0..18446744073709551615"},
        BadValue{{"--device", ""},
                 "--device '': must be a device index, cpu, gpu, auto (the fastest, measured), or part of an "
                 "implementation's name (pocl, intel, nvidia) or a device's"},
        BadValue{{"--camera", "-1"}, "--camera -1: must be an integer >= 0"},
        BadValue{{"--stats-json="}, "--stats-json '': must be a file name"},
        BadValue{{"--integrator", "mlt"}, "--integrator mlt: must be auto, ppm, sppm, pppm, pt, vcm or bpt"},
        BadValue{{"--filter", "mitchell"}, "--filter mitchell: must be box or tent"},
        BadValue{{"--sampler", "halton"}, "--sampler halton: must be sobol, zsobol or independent"},
        BadValue{{"--aperture", "-1"}, "--aperture -1: must be a finite number >= 0 (0 = pinhole)"},
        BadValue{{"--focus-distance", "0"}, "--focus-distance 0: must be a finite number > 0"},
        BadValue{{"--direct", "both"}, "--direct both: must be photons or sample"},
        BadValue{{"--spp", "0"}, "--spp 0: must be an integer in 1..256"},
        BadValue{{"--spp", "257"}, "--spp 257: must be an integer in 1..256"},
        BadValue{{"--max-bounces", "0"}, "--max-bounces 0: must be an integer in 1..1024"},
        BadValue{{"--max-bounces", "1025"}, "--max-bounces 1025: must be an integer in 1..1024"},
        BadValue{{"--progressive-output", "-1"}, "--progressive-output -1: must be an integer >= 0 (0 = off)"},
        BadValue{{"--kernel-dir="}, "--kernel-dir '': must be a directory"},
        BadValue{{"--dump-kernel-source="}, "--dump-kernel-source '': must be a file name"}));

TEST(Options, ErrorEstimation) {
    CommandLine d = parse_options(Args{});
    EXPECT_EQ(d.render.target_error, 0.0);
    EXPECT_FALSE(d.render.confidence.has_value());
    EXPECT_EQ(confidence_of(d.render), 0.95);
    EXPECT_EQ(d.render.error_output, "");
    EXPECT_FALSE(wants_error_estimate(d.render));
    CommandLine o = parse_options(
        Args{"--integrator", "sppm", "--target-error", "0.05", "--confidence=0.9", "--error-output", "e.exr"});
    EXPECT_EQ(o.render.target_error, 0.05);
    EXPECT_EQ(o.render.confidence, 0.9);
    EXPECT_EQ(o.render.error_output, "e.exr");
    EXPECT_TRUE(wants_error_estimate(o.render));
    EXPECT_FALSE(o.render.error_bound);
    // The integrator may come after the option; every integrator estimates.
    EXPECT_TRUE(wants_error_estimate(parse_options(Args{"--error-output", "e.exr", "--integrator", "pppm"}).render));
    EXPECT_TRUE(wants_error_estimate(parse_options(Args{"--integrator", "ppm", "--target-error", "0.1"}).render));
    EXPECT_TRUE(parse_options(Args{"--target-error", "0.1", "--error-bound"}).render.error_bound);
    EXPECT_TRUE(wants_error_estimate(parse_options(Args{"--integrator", "pt", "--target-error", "0.1"}).render));
    EXPECT_EQ(error_of({"--error-bound"}), "--error-bound: needs --target-error");
    EXPECT_EQ(error_of({"--integrator", "sppm", "--confidence", "0.9"}),
              "--confidence: needs --target-error or --error-output");
    EXPECT_EQ(error_of({"--target-error", "0"}), "--target-error 0: must be a number > 0");
    EXPECT_EQ(error_of({"--target-error", "nan"}), "--target-error nan: must be a number > 0");
    EXPECT_EQ(error_of({"--confidence", "1"}), "--confidence 1: must be in (0, 1)");
    EXPECT_EQ(error_of({"--confidence", "0"}), "--confidence 0: must be in (0, 1)");
    EXPECT_EQ(error_of({"--error-output", "e.png"}), "--error-output e.png: must be a file name ending in .exr");
}

TEST(Options, ArgcArgv) {
    const char* argv[] = {"clppm", "--passes=3", "box.glb"};
    CommandLine o = parse_options(3, const_cast<char**>(argv));
    EXPECT_EQ(o.render.passes, 3u);
    EXPECT_EQ(o.render.scene, "box.glb");
}

// usage() with line wrapping undone, so that a fragment may span a wrapped line.
std::string unwrapped_usage() {
    std::string text;
    for (char c : usage()) {
        if (c == ' ' && !text.empty() && text.back() == ' ') continue;
        text += c == '\n' ? ' ' : c;
    }
    return text;
}

TEST(Options, UsageListsEveryOptionWithDefaultAndRange) {
    std::string text = unwrapped_usage();
    for (const char* name : {"-o, --output FILE",
                             "--no-png",
                             "--width N",
                             "--height N",
                             "--passes N",
                             "--time SECONDS",
                             "--photons N",
                             "--alpha A",
                             "--radius R",
                             "--seed S",
                             "--list-devices",
                             "--device SPEC",
                             "--camera N",
                             "--quiet",
                             "--stats-json FILE",
                             "--integrator NAME",
                             "--direct MODE",
                             "--spp N",
                             "--max-bounces N",
                             "--progressive-output K",
                             "--kernel-dir DIR",
                             "--dump-kernel-source FILE",
                             "--target-error E",
                             "--confidence P",
                             "--error-output FILE",
                             "-h, --help",
                             "--version"})
        EXPECT_NE(text.find(name), std::string::npos) << name;
    for (const char* fragment :
         {"Default: clppm.exr", "Default: 0.7", "in (0, 1]", "Default: 200000", "Default: 16", "1..256",
          "Default: auto", "Default: sample", "Default: 64", "Default: 0.95", "in (0, 1)"})
        EXPECT_NE(text.find(fragment), std::string::npos) << fragment;
}

// --help comes from the CLI11 App: sections by group, in this order, the subcommands and the
// environment variables.
TEST(Options, UsageIsGroupedWithSubcommandsAndEnvironment) {
    const std::string text = usage();
    size_t at = 0;
    for (const char* section : {"Usage: clppm [render] [options]", "Positionals:", "Output:", "Image and camera:",
                                "Integrator:", "Error estimation:", "Lighting:", "Checkpoints:", "Devices and kernels:",
                                "Other:", "Subcommands:", "Environment:"}) {
        const size_t p = text.find(section, at);
        EXPECT_NE(p, std::string::npos) << section << " (in order)";
        if (p != std::string::npos) at = p;
    }
    for (const char* fragment : {"  render ", "  compare ", "CLPPM_CACHE_DIR", "POCL_DEVICES"})
        EXPECT_NE(text.find(fragment), std::string::npos) << fragment;
    // Every line fits in 100 columns.
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) EXPECT_LE(line.size(), 100u) << line;
}

// `clppm render ...` is `clppm ...`.
TEST(Options, RenderSubcommand) {
    CommandLine o = parse_options(Args{"render", "--passes", "3", "x.gltf"});
    EXPECT_EQ(o.render.passes, 3u);
    EXPECT_EQ(o.render.scene, "x.gltf");
    EXPECT_EQ(error_of({"render", "--alpha", "2"}), "--alpha 2: must be in (0, 1]");
    // Repeated options: the last wins, --device collects every one.
    EXPECT_EQ(parse_options(Args{"--passes", "3", "--passes=5"}).render.passes, 5u);
    EXPECT_EQ(parse_options(Args{"--device", "a", "--device", "b"}).render.devices,
              (std::vector<std::string>{"a", "b"}));
}

TEST(Options, EnumNames) {
    EXPECT_STREQ(integrator_row("BDPT").name, "bpt"); // pbrt's name for it
    EXPECT_EQ(parse_options(Args{"--integrator", "BDPT"}).render.settings.integrator, "bpt");
    EXPECT_EQ(integrator_names(), "ppm, sppm, pppm, pt, vcm or bpt");
    EXPECT_STREQ(to_string(DirectLighting::Photons), "photons");
    EXPECT_STREQ(to_string(DirectLighting::Sample), "sample");
}

} // namespace
} // namespace clppm

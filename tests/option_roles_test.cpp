// One table says what each option is to a render's result (render/option_table.h, OptionRole), and
// the lists that must agree derive from it: what every MPI process shares, what a checkpoint
// continues only under (issue 61: --disc-coverage was in the one and not the other). These tests
// catch a wrong row: each option has a sample value here (a new option fails until it gets one);
// every Image and Run option's value reads back what its sample set; and a render with each Local
// option set gives the same image, bit for bit, as one without.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "render/option_table.h"
#include "render/render_options.h"
#include "test_util.h"
#include "util/error.h"

using namespace clppm;
using namespace clppm::test;

namespace {

// A value of each option other than its default ("" for a flag).
const std::map<std::string, std::string>& samples() {
    static const std::map<std::string, std::string> s = {{"--output", "other.exr"},
                                                         {"--no-png", ""},
                                                         {"--tonemap", "reinhard"},
                                                         {"--exposure", "1.5"},
                                                         {"--auto-exposure", ""},
                                                         {"--stats-json", "stats.json"},
                                                         {"--progressive-output", "1"},
                                                         {"--serve", "0"},
                                                         {"--display-server", "127.0.0.1:1"},
                                                         {"--quiet", ""},
                                                         {"--width", "12"},
                                                         {"--height", "10"},
                                                         {"--variant", "Red"},
                                                         {"--camera", "1"},
                                                         {"--aperture", "0.1"},
                                                         {"--focus-distance", "2"},
                                                         {"--filter", "tent"},
                                                         {"--integrator", "ppm"},
                                                         {"--passes", "5"},
                                                         {"--time", "1"},
                                                         {"--photons", "1234"},
                                                         {"--alpha", "0.5"},
                                                         {"--radius", "0.05"},
                                                         {"--spp", "2"},
                                                         {"--disc-coverage", "on"},
                                                         {"--volume-gather", "beams"},
                                                         {"--direct", "photons"},
                                                         {"--max-bounces", "3"},
                                                         {"--sampler", "independent"},
                                                         {"--visual-importance", ""},
                                                         {"--seed", "9"},
                                                         {"--target-error", "0.1"},
                                                         {"--error-bound", ""},
                                                         {"--confidence", "0.9"},
                                                         {"--error-output", "e.exr"},
                                                         {"--env", "studio"},
                                                         {"--env-color", "1,0,0"},
                                                         {"--env-strength", "2"},
                                                         {"--env-rotate", "30"},
                                                         {"--env-hidden", ""},
                                                         {"--no-default-light", ""},
                                                         {"--medium-density", "0.5"},
                                                         {"--medium-albedo", "0.8,0.9,1"},
                                                         {"--medium-anisotropy", "0.3"},
                                                         {"--medium-scale", "2"},
                                                         {"--no-medium", ""},
                                                         {"--checkpoint", "c.ckpt"},
                                                         {"--checkpoint-every", "1"},
                                                         {"--checkpoint-interval", "1"},
                                                         {"--resume", "r.ckpt"},
                                                         {"--device", "0"},
                                                         {"--generic-kernels", ""},
                                                         {"--kernel-dir", "/tmp"},
                                                         {"--dump-kernel-source", "k.cl"}};
    return s;
}

RenderOptions with(const RenderOptionSpec& spec) {
    RenderOptions o;
    apply_render_option(o, spec, spec.name, samples().at(spec.name));
    return o;
}

} // namespace

TEST(OptionRoles, EveryOptionHasASampleAndItsRolesValue) {
    for (const RenderOptionSpec& spec : render_option_table()) {
        ASSERT_TRUE(samples().count(spec.name)) << spec.name << ": give it a sample value here, and check its role";
        EXPECT_EQ(spec.value == nullptr, spec.role == OptionRole::Local)
            << spec.name << ": Image and Run options read their value back, Local ones have none";
    }
    EXPECT_EQ(samples().size(), render_option_table().size()) << "a sample for an option that is gone";
}

// The value an Image or Run option reports is the one its sample set, and the lists built from the
// roles carry it: every process's agreement and, for Image, the checkpoint's fingerprint.
TEST(OptionRoles, ImageAndRunOptionsReadBackWhatTheySet) {
    const RenderOptions defaults;
    for (const RenderOptionSpec& spec : render_option_table()) {
        if (spec.role == OptionRole::Local) continue;
        const RenderOptions o = with(spec);
        EXPECT_NE(spec.value(o), spec.value(defaults))
            << spec.name << " " << samples().at(spec.name) << ": its value reads another field than it sets";
        const Json shared = options_every_rank_shares(o);
        ASSERT_TRUE(shared.contains(spec.name)) << spec.name;
        EXPECT_EQ(shared[spec.name], spec.value(o)) << spec.name;
        EXPECT_EQ(option_values(o, OptionRole::Image).contains(spec.name), spec.role == OptionRole::Image) << spec.name;
    }
    // The drift issue 61 found: --disc-coverage shapes the image and every process must share it.
    EXPECT_EQ(find_render_option("--disc-coverage")->role, OptionRole::Image);
}

// --help's "Default: X" is the value an Image or Run option has when it is not given, wherever X is a
// plain number or word (the rest describe where the value comes from: "the camera's, else 0").
TEST(OptionRoles, HelpsDefaultIsTheValueWhenNotGiven) {
    const RenderOptions defaults;
    int checked = 0;
    for (const RenderOptionSpec& spec : render_option_table()) {
        if (spec.role == OptionRole::Local || !spec.default_text) continue;
        const std::string text = spec.default_text;
        const Json value = spec.value(defaults);
        char* end = nullptr;
        const double number = std::strtod(text.c_str(), &end);
        if (!text.empty() && *end == '\0') {
            ASSERT_TRUE(value.is_number())
                << spec.name << ": --help says " << text << ", the value is " << value.dump();
            EXPECT_EQ(value.get<double>(), number) << spec.name;
            ++checked;
        } else if (text.find_first_of(" ,'") == std::string::npos && value.is_string() &&
                   !value.get<std::string>().empty()) { // "none", "embedded": an empty value in words
            EXPECT_EQ(value.get<std::string>(), text) << spec.name;
            ++checked;
        }
    }
    EXPECT_GE(checked, 14) << "fewer plain defaults than the table had when this test was written";
}

// A Local option changes how the render runs and reports, never its image: the EXR is the same bit
// for bit with each set. (--serve and --display-server open sockets: their images are the same
// too, but a test that listens or connects is left to tests/live_view_test.cpp and tev_client_test.)
TEST(OptionRoles, LocalOptionsLeaveTheImageAlone) {
    const std::string dir = make_temp_dir("option_roles"), out = dir + "/base.exr";
    const std::string common = " --width 12 --height 10 --passes 2 --photons 2000 --seed 3 --integrator sppm";
    std::string log;
    ASSERT_EQ(run_clppm(common + " --no-png -o " + out, &log), 0) << log;
    const Image base = read_exr(out);
    for (const RenderOptionSpec& spec : render_option_table()) {
        if (spec.role != OptionRole::Local) continue;
        const std::string name = spec.name;
        if (name == "--serve" || name == "--display-server") continue;
        std::string value = samples().at(name);
        if (name == "--device") value = std::to_string(test_device().index);
        else if (value.find(".exr") != std::string::npos || value.find(".json") != std::string::npos ||
                 value.find(".ckpt") != std::string::npos || value.find(".cl") != std::string::npos)
            value = dir + "/" + value; // a file it writes
        const std::string target = name == "--output" ? value : dir + "/x.exr";
        const std::string args = common + " --no-png " + name + (value.empty() ? "" : " " + value) +
                                 (name == "--output" ? "" : " -o " + target);
        ASSERT_EQ(run_clppm(args, &log), 0) << name << ": " << log;
        EXPECT_EQ(read_exr(target).rgb, base.rgb) << name << " " << value << " changed the image: is it Local?";
    }
}

// An option that takes one of a list of names reads them from one place (util/enum_names.h beside
// each enum, the integrator table): every name its range lists is accepted in any case and reads
// back as itself, and a name it does not list is refused with the range in the message.
TEST(OptionRoles, ChoiceOptionsTakeEveryNameTheirRangeLists) {
    for (const char* option : {"--filter", "--sampler", "--disc-coverage", "--direct", "--integrator", "--tonemap"}) {
        const RenderOptionSpec* spec = find_render_option(option);
        ASSERT_NE(spec, nullptr) << option;
        std::string range = spec->range;
        std::vector<std::string> names;
        for (size_t start = 0; start < range.size();) {
            size_t end = range.find_first_of(", ", start);
            if (end == std::string::npos) end = range.size();
            const std::string word = range.substr(start, end - start);
            if (!word.empty() && word != "or") names.push_back(word);
            start = end + 1;
        }
        ASSERT_GE(names.size(), 2u) << option << " " << range;
        for (const std::string& name : names) {
            RenderOptions o;
            std::string shouted = name;
            for (char& c : shouted) c = char(std::toupper(static_cast<unsigned char>(c)));
            ASSERT_NO_THROW(apply_render_option(o, *spec, option, shouted)) << option << " " << shouted;
            const Json got = spec->value ? spec->value(o) : Json(to_string(o.tone.curve));
            EXPECT_EQ(got, Json(name)) << option << " " << shouted;
        }
        RenderOptions o;
        try {
            apply_render_option(o, *spec, option, "bogus");
            ADD_FAILURE() << option << " bogus was accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(range), std::string::npos) << e.what();
        }
    }
}

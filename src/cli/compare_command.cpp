#include "cli/compare_command.h"

#include <cctype>
#include <cstdio>
#include <memory>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/help_formatter.h"
#include "io/image_compare.h"
#include "io/image_io.h"
#include "io/stats_json.h"
#include "util/error.h"
#include "util/text.h"

namespace clppm {
namespace {

constexpr const char* kUsage = " (usage: clppm compare A.exr REFERENCE.exr [--diff OUT.png] [--box K])";

struct CompareArgs {
    std::vector<std::string> files;
    std::string diff_png, box_text;
    bool help = false;
};

std::unique_ptr<CLI::App> make_compare_app(CompareArgs& a) {
    auto app = std::make_unique<CLI::App>(
        "Prints, as JSON, how far IMAGE is from REFERENCE: both means and their ratio, the relative MSE\n"
        "(per pixel and channel, (a - b)^2 / (b^2 + 0.01)), RMSE, relative RMSE, the RMSE of the sRGB\n"
        "codes, p90_rel_error (the 90th percentile over pixels of |Y_a - Y_b| / max(Y_b, 1% of the mean Y_b)\n"
        "on luminance: the measure --target-error states) and NaN/Inf counts.",
        "clppm compare");
    app->set_help_flag();
    app->formatter(std::make_shared<HelpFormatter>(
        "Usage: clppm compare IMAGE.exr REFERENCE.exr [--diff OUT.png] [--box K]\n", 22));
    app->add_option("files", a.files, "IMAGE.exr and REFERENCE.exr")->type_name("");
    app->add_option("--diff", a.diff_png, "also write a false-colour difference image")->type_name("OUT.png");
    app->add_option("--box", a.box_text,
                    wrapped("also the relative MSE of both images box-filtered over K x K pixels (box_rel_mse: bias "
                            "more than noise); K in 1..1024",
                            74))
        ->type_name("K");
    app->add_flag("-h,--help", a.help, "print this help and exit");
    return app;
}

bool ends_with_png(const std::string& s) { return s.size() > 4 && ends_with_ci(s, ".png"); }

} // namespace

std::string compare_usage() {
    CompareArgs a;
    return make_compare_app(a)->help();
}

int compare_command(int argc, char** argv) {
    CompareArgs a;
    std::unique_ptr<CLI::App> app = make_compare_app(a);
    std::vector<std::string> args;
    for (int i = argc - 1; i >= 0; --i) args.emplace_back(argv[i]); // CLI11 takes them last first
    try {
        app->parse(args);
    } catch (const CLI::ParseError& e) {
        if (a.help) {
            std::fputs(compare_usage().c_str(), stdout);
            return 0;
        }
        throw Error(std::string("compare: ") + e.what() + kUsage);
    }
    if (a.help) {
        std::fputs(compare_usage().c_str(), stdout);
        return 0;
    }
    if (app->count("--diff") && !ends_with_png(a.diff_png))
        throw Error("compare --diff " + a.diff_png + ": must be a file name ending in .png (it is written as PNG)");
    int box = 0;
    if (app->count("--box")) {
        char* end = nullptr;
        const long k = std::strtol(a.box_text.c_str(), &end, 10);
        if (a.box_text.empty() || *end != '\0' || k < 1 || k > 1024)
            throw Error("compare --box " + (a.box_text.empty() ? std::string("''") : a.box_text) +
                        ": must be an integer in 1..1024");
        box = int(k);
    }
    if (a.files.size() != 2) throw Error(std::string("compare: expected two EXR files") + kUsage);
    Image img = read_exr(a.files[0]), ref = read_exr(a.files[1]);
    ImageDifference d = compare_images(img, ref);
    if (box > 0 && (img.width < box || img.height < box))
        throw Error("compare --box " + std::to_string(box) + ": larger than the images");
    if (!a.diff_png.empty()) write_png(a.diff_png, difference_image(img, ref));
    Json j;
    j["image"] = a.files[0];
    j["reference"] = a.files[1];
    j["pixels"] = d.pixels;
    j["nonfinite_image"] = d.nonfinite_a;
    j["nonfinite_reference"] = d.nonfinite_b;
    j["mean_image"] = d.mean_a;
    j["mean_reference"] = d.mean_b;
    j["mean_ratio"] = d.mean_b > 0 ? d.mean_a / d.mean_b : 0.0;
    j["rel_mse"] = d.rel_mse;
    j["rmse"] = d.rmse;
    j["rel_rmse"] = d.rel_rmse;
    j["rmse_srgb"] = d.rmse_srgb;
    j["p90_rel_error"] = d.p90_rel_error;
    if (box > 0) {
        j["box"] = box;
        j["box_rel_mse"] = compare_images(box_filter(img, box), box_filter(ref, box)).rel_mse;
    }
    std::fputs(to_json_text(j).c_str(), stdout);
    return 0;
}

} // namespace clppm

// The world's participating medium (kernels/medium.cl) against closed forms and quadratures written
// here on the host:
// - a pure absorber between the camera and glowing walls is Beer-Lambert's exp(-sigma_t d) per
//   channel, also where an index-matched glass cube that encloses its own volume takes part of the
//   way out of the fog;
// - a medium that scatters everything it stops, inside a furnace whose walls glow Le and reflect
//   rho, leaves the radiance Le / (1 - rho) everywhere, whatever its colour and anisotropy (the
//   distance sampling over the channels, the light samples from the medium and the MIS against the
//   phase function all take part);
// - single scattering from a point light, integrated along each pixel's ray by quadrature, with a
//   Henyey-Greenstein g of 0.6 and a chromatic medium;
// - a surface's light samples lose exp(-sigma_t r) on their way through the medium;
// - extras.clppm_medium and the --medium options, their messages, and the integrators that do not
//   render media saying so.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "medium_scenes.h"
#include "scene/device_scene.h"
#include "scene/gltf/gltf_load.h"
#include "scene/medium.h"
#include "scene_builders.h"
#include "test_util.h"
#include "util/error.h"

using namespace clppm;
using namespace clppm::test;

TEST(Medium, AbsorberIsBeerLambert) {
    const std::array<float, 3> sigma{0.3f, 1.f, 2.5f};
    Scene scene = glowing_box(0.f, 1.f);
    set_medium(scene, sigma, {0.f, 0.f, 0.f}, 0.f);
    const Rendered r = render_box(scene);
    for (int c = 0; c < 3; ++c) {
        auto ref = [&](D3 d) {
            double t_in, t_out;
            slab({0, 0, 0}, d, {0, 0, 0}, 1.0, &t_in, &t_out);
            return std::exp(-sigma[size_t(c)] * t_out);
        };
        expect_region(r.img, r.cam, 0, 24, c, 0.01, ref, "the whole image");
        expect_region(r.img, r.cam, 8, 16, c, 0.015, ref, "the centre");
    }
}

// A glass cube of ior 1 that encloses a clear volume of its own: inside it the fog stops, so the
// wall behind it is seen through less fog. Light samples and rays alike pass its faces unbent.
TEST(Medium, AClosedVolumeKeepsTheFogOut) {
    const std::array<float, 3> sigma{0.5f, 1.f, 2.f};
    Scene scene = glowing_box(0.f, 1.f);
    const uint32_t glass = add_material(scene, 1, 1, 1, 0, false, MAT_GLASS, 1.f, 0.f);
    scene.materials[glass].flags |= MATERIAL_FLAG_ENCLOSES_VOLUME;
    const D3 centre{0, 0, -0.6};
    add_box(scene, {0, 0, -0.6f}, 0.3f, glass, false);
    set_medium(scene, sigma, {0.f, 0.f, 0.f}, 0.f);
    const Rendered r = render_box(scene);
    const Image& img = r.img;
    for (int c = 0; c < 3; ++c) {
        auto ref = [&](D3 d) {
            double t_in, t_out, c_in, c_out;
            slab({0, 0, 0}, d, {0, 0, 0}, 1.0, &t_in, &t_out);
            slab({0, 0, 0}, d, centre, 0.3, &c_in, &c_out);
            const double inside = c_out > c_in && c_in > 0 ? c_out - c_in : 0.0;
            return std::exp(-sigma[size_t(c)] * (t_out - inside));
        };
        expect_region(img, r.cam, 0, 24, c, 0.01, ref, "the whole image");
        expect_region(img, r.cam, 9, 15, c, 0.015, ref, "through the cube");
    }
    // The cube is there to be seen: without its volume the centre is darker.
    scene.materials[glass].flags &= ~MATERIAL_FLAG_ENCLOSES_VOLUME;
    const Image fogged = render_passes(scene, pt_settings(24), 64);
    EXPECT_LT(region_mean(fogged, 9, 9, 15, 15, 2), 0.8 * region_mean(img, 9, 9, 15, 15, 2));
}

TEST(Medium, ScatteringFurnaceKeepsItsRadiance) {
    // Walls of albedo 0.5 glowing 1: radiance 2 everywhere, with or without a medium that absorbs nothing.
    for (float g : {0.f, 0.6f, -0.4f}) {
        SCOPED_TRACE("g " + std::to_string(g));
        Scene scene = glowing_box(0.5f, 1.f);
        set_medium(scene, {0.5f, 1.f, 2.f}, {1.f, 1.f, 1.f}, g);
        const Image img = render_passes(scene, pt_settings(16, 1024), 512);
        expect_clean(img);
        // One standard error of the mean is 0.0065 in the densest channel at 512 passes.
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(region_mean(img, 0, 0, 16, 16, c), 2.0, 0.025) << "channel " << c;
    }
}

// One scattering event between the camera and the black walls, lit by a point light:
// L = int_0^d sigma_s e^(-sigma_t t) p(cos) I / r^2 e^(-sigma_t r) dt along each pixel's ray.
TEST(Medium, SingleScatteringFromAPointLight) {
    const PointLightInFog fog;
    const Scene scene = fog.scene();
    const RenderSettings s = pt_settings(24, 1);
    const Image img = render_passes(scene, s, 1024);
    expect_clean(img);
    const dev::Camera cam = camera_of(scene, s);
    for (int c = 0; c < 3; ++c) {
        const std::function<double(D3)> ref = fog.reference(c);
        expect_region(img, cam, 0, 24, c, 0.02, ref, "the whole image");
        expect_region(img, cam, 12, 20, c, 0.03, ref, "towards the light");
    }
}

// plane_under_point_light in a medium that only absorbs: the plane's closed form times
// exp(-sigma_t (r_light + r_camera)).
TEST(Medium, LightSamplesCrossTheMedium) {
    const double rho = 0.5, I = 4, h = 1.5, sigma = 0.2;
    Scene scene = plane_under_point_light(float(rho), float(I), float(h));
    set_medium(scene, {float(sigma), float(sigma), float(sigma)}, {0.f, 0.f, 0.f}, 0.f);
    const RenderSettings s = pt_settings(24, 1);
    const Image img = render_passes(scene, s, 256);
    expect_clean(img);
    float bmin[3] = {-4, 0, -4}, bmax[3] = {4, 0, 4};
    const dev::Camera cam = make_camera(scene, s, bmin, bmax, nullptr);
    const D3 eye = d3(cam.origin);
    auto ref = [&](D3 d) {
        const double t = -eye.y / d.y;
        const D3 x = eye + t * d;
        const double d2 = x.x * x.x + x.z * x.z + h * h;
        return rho / M_PI * I * (h / std::sqrt(d2)) / d2 * std::exp(-sigma * (std::sqrt(d2) + t));
    };
    expect_region(img, cam, 4, 20, 1, 0.01, ref, "the plane");
}

// The sun and the environment lie at infinity: through an unbounded medium nothing of them arrives
// in a channel with extinction (as rays that leave the scene find, and as Cycles' world volume
// has it), and all of it in a clear channel.
TEST(Medium, DistantLightsReachOnlyThroughClearChannels) {
    const float rho = 0.5f, E = 3.f;
    Scene scene = plane_under_point_light(rho, 0.f, 1.f);
    scene.punctual_lights.clear();
    add_directional_light(scene, {0, -1, 0}, E);
    Environment env;
    env.present = true;
    env.radiance = {0.5f, 0.5f, 0.5f};
    scene.environment = env;
    set_medium(scene, {0.f, 0.3f, 0.3f}, {0.5f, 0.5f, 0.5f}, 0.f);
    const Image img = render_passes(scene, pt_settings(16, 4), 64);
    expect_clean(img);
    // The clear channel: the sun's rho E / pi and the world's rho L over the plane's upper side
    // (the plane, 8 x 8 seen from 3 above, hides little of the sky from its own centre).
    EXPECT_NEAR(region_mean(img, 6, 6, 10, 10, 0), rho * E / M_PI + rho * 0.5, 0.02);
    EXPECT_EQ(region_mean(img, 0, 0, 16, 16, 1), 0.0);
    EXPECT_EQ(region_mean(img, 0, 0, 16, 16, 2), 0.0);
}

// ---- a mesh's own medium (KHR_materials_volume_scatter) -------------------------------------

// The furnace again with the medium inside a closed mesh: no light samples leave it, so the walls'
// light reaches the medium through rays the phase function sends out of the cube alone.
TEST(Medium, ScatteringMeshKeepsTheFurnacesRadiance) {
    const Image img =
        render_passes(scattering_cube(0.5f, {0.5f, 1.f, 2.f}, {1.f, 1.f, 1.f}, 0.4f), pt_settings(16, 1024), 512);
    expect_clean(img);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(region_mean(img, 0, 0, 16, 16, c), 2.0, 0.03) << "channel " << c;
}

// The same medium as the world's and as the cube's (which leaves a gap of 0.001 by the walls)
// renders alike: two ways to the same light, one with light samples and one without.
TEST(Medium, AMeshsMediumIsTheWorldsMediumInside) {
    const std::array<float, 3> sigma{0.6f, 1.f, 1.5f}, albedo{0.9f, 0.7f, 0.5f};
    Scene world = glowing_box(0.5f, 1.f);
    set_medium(world, sigma, albedo, 0.5f);
    const Image a = render_passes(world, pt_settings(16, 1024), 256);
    const Image b = render_passes(scattering_cube(0.5f, sigma, albedo, 0.5f), pt_settings(16, 1024), 1024);
    expect_clean(b);
    for (int c = 0; c < 3; ++c) {
        const double wa = region_mean(a, 0, 0, 16, 16, c), wb = region_mean(b, 0, 0, 16, 16, c);
        EXPECT_NEAR(wb / wa, 1.0, 0.03) << "channel " << c << ": mesh " << wb << ", world " << wa;
    }
}

TEST(Medium, VolumeScatterExtensionIsRead) {
    const std::string dir = make_temp_dir("medium_scatter");
    nlohmann::json g = nlohmann::json::parse(slurp(std::string(CLPPM_TEST_DATA) + "/volume_slab.gltf"));
    g["materials"][0]["extensions"]["KHR_materials_volume_scatter"] = {{"multiscatterColor", {0.5, 0.0, 1.0}},
                                                                       {"scatterAnisotropy", 0.3}};
    const std::string path = dir + "/scatter.gltf";
    std::ofstream(path) << g.dump();
    const Scene s = load_gltf(path);
    const dev::Material& m = s.materials[0];
    // s = 4.09712 + 4.20863 rho - sqrt(9.59217 + 41.6808 rho + 17.7126 rho^2), rho_ss = 1 - s^2
    EXPECT_NEAR(m.scatter[0], 0.911713, 1e-5);
    EXPECT_NEAR(m.scatter[1], 0.0, 1e-5) << "a multiscatter albedo of 0 is a single-scattering albedo of 0";
    EXPECT_NEAR(m.scatter[2], 1.0, 1e-5);
    EXPECT_FLOAT_EQ(m.scatter[3], 0.3f);
    EXPECT_TRUE(scene_has_media(s));
    // Without an attenuation there is nothing to scatter: said, and ignored.
    g["materials"][0]["extensions"]["KHR_materials_volume"].erase("attenuationDistance");
    std::ofstream(path) << g.dump();
    const Scene t = load_gltf(path);
    EXPECT_EQ(t.materials[0].scatter[0], 0.f);
    ASSERT_FALSE(t.warnings.empty());
    EXPECT_NE(t.warnings[0].find("KHR_materials_volume_scatter has no effect"), std::string::npos) << t.warnings[0];
}

// ---- the file's medium and the options -------------------------------------------------------

namespace {

std::string data(const std::string& name) { return std::string(CLPPM_TEST_DATA) + "/" + name; }

// tests/data/<scene> with `medium` as its scene's extras.clppm_medium, written into dir.
std::string with_medium(const std::string& dir, const std::string& scene, const nlohmann::json& medium) {
    nlohmann::json g = nlohmann::json::parse(slurp(data(scene)));
    g["scenes"][0]["extras"]["clppm_medium"] = medium;
    const std::string path = dir + "/" + scene;
    std::ofstream(path) << g.dump();
    return path;
}

std::string load_error(const std::string& path) {
    try {
        load_gltf(path);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST(Medium, FileMediumAndItsErrors) {
    const std::string dir = make_temp_dir("medium_file");
    Scene s = load_gltf(with_medium(dir, "rough_volume_clear.gltf",
                                    {{"density", {0.1, 0.2, 0.3}}, {"albedo", 0.8}, {"anisotropy", -0.3}}));
    ASSERT_TRUE(s.has_file_medium);
    EXPECT_FLOAT_EQ(s.file_medium.density[2], 0.3f);
    EXPECT_FLOAT_EQ(s.file_medium.albedo[1], 0.8f);
    EXPECT_FLOAT_EQ(s.file_medium.anisotropy, -0.3f);
    const std::pair<nlohmann::json, const char*> bad[] = {
        {{{"albedo", 0.5}}, "must have a \"density\""},
        {{{"density", -1}}, "extras.clppm_medium.density must be finite, from 0"},
        {{{"density", 1}, {"albedo", 1.5}}, "extras.clppm_medium.albedo must be finite, from 0 to 1"},
        {{{"density", 1}, {"anisotropy", 1}}, "anisotropy must be a number above -1 and below 1"},
        {{{"density", {1, 2}}}, "density must be a number or [r, g, b]"},
        {{{"density", 1}, {"colour", 1}}, "unknown key \"colour\""},
        {nlohmann::json(3), "must be an object"},
    };
    for (const auto& [medium, message] : bad) {
        const std::string e = load_error(with_medium(dir, "rough_volume_clear.gltf", medium));
        EXPECT_NE(e.find(message), std::string::npos) << medium.dump() << ": " << e;
        EXPECT_NE(e.find("rough_volume_clear.gltf"), std::string::npos) << e;
    }
}

TEST(Medium, OptionsOverrideScaleAndRemoveIt) {
    Scene scene = glowing_box(0.f, 1.f);
    MediumSettings none;
    std::string note;
    apply_medium(scene, none, &note);
    EXPECT_FALSE(scene.medium.present);
    EXPECT_EQ(note, "");
    scene.has_file_medium = true;
    scene.file_medium = MediumDesc{{1, 2, 3}, {0.5f, 0.5f, 0.5f}, 0.2f};
    MediumSettings o;
    o.has_albedo = true;
    o.albedo = {0.9f, 0.9f, 0.9f};
    o.scale = 2;
    apply_medium(scene, o, &note);
    ASSERT_TRUE(scene.medium.present);
    EXPECT_FLOAT_EQ(scene.medium.medium.density[2], 6.f);
    EXPECT_FLOAT_EQ(scene.medium.medium.albedo[0], 0.9f);
    EXPECT_FLOAT_EQ(scene.medium.medium.anisotropy, 0.2f);
    EXPECT_NE(note.find("changed by the --medium options"), std::string::npos) << note;
    MediumSettings remove;
    remove.none = true;
    apply_medium(scene, remove, &note);
    EXPECT_FALSE(scene.medium.present);
    remove.scale = 3;
    EXPECT_THROW(apply_medium(scene, remove, &note), Error);
    scene.has_file_medium = false;
    EXPECT_THROW(apply_medium(scene, o, &note), Error) << "--medium-albedo without a medium";
    MediumSettings zero;
    zero.has_density = true;
    apply_medium(scene, zero, &note);
    EXPECT_FALSE(scene.medium.present) << "density 0 is no medium";
}

TEST(Medium, CommandLineRendersAndRefusesWhatCannot) {
    const std::string dir = make_temp_dir("medium_cli"), out = dir + "/m.exr";
    const std::string scene = with_medium(dir, "rough_volume_clear.gltf", {{"density", 0.3}, {"albedo", 0.9}});
    std::string log;
    ASSERT_EQ(run_clppm(scene + " --width 16 --height 16 --passes 4 --no-png -o " + out, &log), 0) << log;
    // glass under a point light in fog: the default takes photons for the volumetric caustics
    EXPECT_NE(log.find("integrator sppm: the world has a participating medium"), std::string::npos) << log;
    EXPECT_NE(log.find("volumetric caustics"), std::string::npos) << log;
    // photons per pass: 10000 in media unless --photons says
    EXPECT_NE(log.find("photons: 10000 per pass in participating media"), std::string::npos) << log;
    ASSERT_EQ(run_clppm(scene + " --width 16 --height 16 --passes 1 --photons 3000 --no-png -o " + out +
                            " --stats-json " + dir + "/s.json",
                        &log),
              0)
        << log;
    EXPECT_EQ(log.find("photons: "), std::string::npos) << log;
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(dir + "/s.json"))["photons_per_pass"], 3000) << log;
    EXPECT_NE(log.find("medium: " + scene + ": extras.clppm_medium: density 0.3 per scene unit, albedo 0.9"),
              std::string::npos)
        << log;
    for (const char* integrator : {"vcm", "bpt"}) {
        EXPECT_NE(
            run_clppm(scene + " --width 16 --height 16 --passes 1 --integrator " + integrator + " -o " + out, &log), 0);
        EXPECT_NE(log.find(std::string("--integrator ") + integrator +
                           ": the scene has a participating medium (extras.clppm_medium, --medium-density or "
                           "KHR_materials_volume_scatter), which only ppm, sppm, pppm or pt can render so far"),
                  std::string::npos)
            << log;
    }
    ASSERT_EQ(
        run_clppm(scene + " --no-medium --integrator sppm --width 16 --height 16 --passes 1 --no-png -o " + out, &log),
        0)
        << log;
    // Beams are SPPM's and PPPM's: another integrator says so rather than gather at points unasked.
    for (const char* integrator : {"pt", "ppm"}) {
        EXPECT_NE(run_clppm(scene + " --width 16 --height 16 --passes 1 --volume-gather beams --integrator " +
                                integrator + " -o " + out,
                            &log),
                  0);
        EXPECT_NE(log.find(std::string("--volume-gather beams: --integrator ") + integrator +
                           " gathers the medium at points; only sppm or pppm gather along beams"),
                  std::string::npos)
            << log;
    }
    ASSERT_EQ(run_clppm(scene +
                            " --no-medium --integrator pt --volume-gather beams --width 16 --height 16 --passes 1 "
                            "--no-png -o " +
                            out,
                        &log),
              0)
        << "without a medium there is nothing to gather: " << log;
    EXPECT_NE(run_clppm(data("rough_volume_clear.gltf") + " --medium-albedo 0.5 -o " + out, &log), 0);
    EXPECT_NE(log.find("give --medium-density"), std::string::npos) << log;
    EXPECT_NE(run_clppm(data("rough_volume_clear.gltf") + " --medium-albedo 1.5 -o " + out, &log), 0);
    EXPECT_NE(log.find("--medium-albedo"), std::string::npos) << log;
}

// What one render is asked to do, independent of how the command line spelled it.
#pragma once
#include <cstdint>
#include <string>

#include "scene/scene_settings.h"
#include "util/enum_names.h"

namespace clppm {

enum class DirectLighting { Photons, Sample };     // --direct
enum class PixelFilter { Box, Tent };              // --filter
enum class Sampler { Sobol, ZSobol, Independent }; // --sampler (the path tracer's)
enum class DiscCoverage { Auto, On, Off };         // --disc-coverage
enum class VolumeGather { Points, Beams };         // --volume-gather

// Their names, spelled here alone (util/enum_names.h): the options parse them, to_string prints them.
constexpr EnumName<DirectLighting> kDirectLightingNames[] = {{DirectLighting::Photons, "photons"},
                                                             {DirectLighting::Sample, "sample"}};
constexpr EnumName<PixelFilter> kPixelFilterNames[] = {{PixelFilter::Box, "box"}, {PixelFilter::Tent, "tent"}};
constexpr EnumName<Sampler> kSamplerNames[] = {
    {Sampler::Sobol, "sobol"}, {Sampler::ZSobol, "zsobol"}, {Sampler::Independent, "independent"}};
constexpr EnumName<DiscCoverage> kDiscCoverageNames[] = {
    {DiscCoverage::Auto, "auto"}, {DiscCoverage::On, "on"}, {DiscCoverage::Off, "off"}};
constexpr EnumName<VolumeGather> kVolumeGatherNames[] = {{VolumeGather::Points, "points"},
                                                         {VolumeGather::Beams, "beams"}};
constexpr const auto& enum_names(DirectLighting) { return kDirectLightingNames; }
constexpr const auto& enum_names(PixelFilter) { return kPixelFilterNames; }
constexpr const auto& enum_names(Sampler) { return kSamplerNames; }
constexpr const auto& enum_names(DiscCoverage) { return kDiscCoverageNames; }
constexpr const auto& enum_names(VolumeGather) { return kVolumeGatherNames; }

// The one set of defaults for what shapes an image, whichever front end asks (the command line,
// the Python module, the tests). The scene's part (camera, resolution, lens, path length) is the
// SceneSettings base.
struct RenderSettings : SceneSettings {
    // A name of integrators/integrator_table.h, or "auto": the default integrator picks one for the
    // scene (integrators/default_integrator.h) before anything is made.
    std::string integrator = "auto";
    DirectLighting direct = DirectLighting::Sample;
    unsigned spp = 4;          // PPM: hit points per pixel (4 anti-alias: bench/RESULTS.md)
    uint64_t photons = 200000; // photons per pass (M)
    double alpha = 0.7;
    double radius = 0; // initial radius in world units; 0: heuristic
    uint64_t seed = 1;
    PixelFilter filter = PixelFilter::Box;
    // The path tracer's numbers: Owen-scrambled Sobol' points over the passes, or independent
    // random streams (bench/RESULTS.md, issue 36). The other integrators draw independent ones.
    Sampler sampler = Sampler::Sobol;
    // The passes the render is planned for (the pass limit; 0: none), which --sampler zsobol's
    // screen-space layout is cut for (kernels/sobol.cl sobol_make_screen). Set by the render job.
    uint64_t planned_passes = 0;
    // PPM and SPPM: photon paths from Markov chains whose target is their visibility to the hit
    // points (Hachisuka and Jensen 2009; integrators/photon_chains.h), not independent ones.
    bool visual_importance = false;
    // PPM, SPPM, PPPM: divide what each hit point gathers by the part of its disc that lies on its
    // surface (kernels/disc_coverage.cl), which removes the darkening where surfaces meet or end.
    // One BVH query a hit point a pass, and about 17 short rays where that query cannot see the disc
    // whole: auto measures it where the hit points number at most twice the photons traced
    // (disc_coverage_wanted).
    DiscCoverage disc_coverage = DiscCoverage::Auto;
    // SPPM and PPPM in media: what estimates the light the camera rays' segments in media scatter
    // towards the eye. points: a volume hit point where the eye path's free flight collides,
    // gathering in a sphere (kernels/gather.cl); beams: each pixel's first scattering segment
    // gathers along its whole length in a cylinder (kernels/beam.cl, the beam radiance estimate),
    // far less noise a pass for far more gather time on this grid (docs/scenes.md, media).
    VolumeGather volume_gather = VolumeGather::Points;
    // VCM and BPT: one technique alone (VCM_MODE_* of kernels/vcm_mis.h), for the tests that
    // compare the techniques; -1: the integrator's own.
    int vcm_techniques = -1;
};

// The defaults with a square image of `size` pixels and `photons` a pass (the tests and benchmarks).
inline RenderSettings square_settings(const std::string& integrator, unsigned size, uint64_t photons) {
    RenderSettings s;
    s.integrator = integrator;
    s.width = s.height = size;
    s.photons = photons;
    return s;
}

// Whether a pass of `hitpoints` hit points and `photons` photons measures its discs' coverage:
// always (on), never (off), or (auto) where the hit points number at most twice the photons. A hit
// point inside a flat surface costs one BVH query (about 0.09 us on the two-core PoCL CPU), one
// near an edge or where a scanned mesh turns sharply about 17 short rays (0.7 us). At equal time
// the coverage lowered SPPM's box-4 error 2.3x on the Cornell box where hit points were 1.3 times
// the photons, and left the skylit room and a blob of 100k triangles about level; at 4 and 10
// times it was mixed (bench/RESULTS.md, "Gather discs measured at every size"): on at 512 x 512
// with the default 200k photons, off at 1024 x 1024.
bool disc_coverage_wanted(DiscCoverage mode, uint64_t hitpoints, uint64_t photons);

} // namespace clppm

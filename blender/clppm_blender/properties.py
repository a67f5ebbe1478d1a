"""scene.clppm: the render settings of the CLPPM engine, with the library's defaults (the command
line's option table: 0 stands for "the integrator's default" or "none" where the option has no
value of its own)."""
import bpy

# The library's integrators in its order, each described as clppm.integrators() describes it
# (tests/python/test_option_lists.py fails when they part); the labels are the add-on's own.
INTEGRATORS = [
    ("auto", "Auto", "The fastest for the scene (in participating media sppm where glass or smooth metal casts "
                     "caustics from the scene's own lights (volumetric caustics), pt otherwise; without media vcm "
                     "where they cast caustics (sppm for an orthographic camera or --filter tent), sppm where the "
                     "lights reach under 5% of what the camera sees directly (light through a gap), pt otherwise; "
                     "measured: bench/RESULTS.md)"),
    ("ppm", "PPM", "Progressive photon mapping (fixed hit points, Hachisuka et al. 2008)"),
    ("sppm", "SPPM", "Stochastic PPM (a new eye sample per pixel every pass)"),
    ("pppm", "PPPM", "Probabilistic PPM (independent passes, Knaus and Zwicker 2011)"),
    ("pt", "Path tracing", "Path tracing"),
    ("vcm", "VCM", "Vertex connection and merging (bidirectional path tracing and photon merging under MIS)"),
    ("bpt", "BPT", "Bidirectional path tracing"),
]


class ClppmSceneSettings(bpy.types.PropertyGroup):
    integrator: bpy.props.EnumProperty(name="Integrator", items=INTEGRATORS, default="auto")
    passes: bpy.props.IntProperty(name="Passes", min=0, default=0,
                                  description="Stop after this many passes (0: the integrator's default, or none "
                                              "with a time limit)")
    time: bpy.props.FloatProperty(name="Time", min=0.0, default=0.0, unit="TIME_ABSOLUTE",
                                  description="Stop after this many seconds of rendering (0: none)")
    target_error: bpy.props.FloatProperty(name="Target error", min=0.0, max=1.0, default=0.0, precision=3,
                                          description="Stop once the estimated error (90th percentile of the "
                                                      "per-pixel relative error) is at most this (0: off)")
    photons: bpy.props.IntProperty(name="Photons per pass", min=0, max=2147483647, default=0,
                                   description="Photons traced per pass (0: the library's default, 200000, and "
                                               "10000 in participating media, where each collision stores one)")
    alpha: bpy.props.FloatProperty(name="Alpha", min=0.01, max=1.0, default=0.7,
                                   description="Fraction of new photons kept per pass (radius reduction)")
    visual_importance: bpy.props.BoolProperty(
        name="Visual importance", default=False,
        description="PPM and SPPM: photon paths from Markov chains that keep to what the camera sees (Hachisuka "
                    "and Jensen 2009), for light through a gap or a window; one device, no target error")
    device: bpy.props.StringProperty(name="Device", default="",
                                     description="OpenCL device: an index, cpu, gpu, auto (the fastest, measured "
                                                 "once and remembered), an implementation (pocl, intel, nvidia) or "
                                                 "part of a device's name (empty: the first GPU, else PoCL's CPU "
                                                 "device, else the first device)")
    seed: bpy.props.IntProperty(name="Seed", min=0, default=1)
    update_every: bpy.props.FloatProperty(name="Display every", min=0.1, default=0.5, unit="TIME_ABSOLUTE",
                                          description="Seconds between updates of the image while it renders")

    def options(self):
        """The settings as clppm options (keyword arguments of clppm.Renderer)."""
        o = {"integrator": self.integrator, "alpha": self.alpha, "seed": self.seed}
        if self.photons > 0:
            o["photons"] = self.photons
        if self.passes > 0:
            o["passes"] = self.passes
        if self.time > 0:
            o["time"] = self.time
        if self.target_error > 0:
            o["target_error"] = self.target_error
        if self.device:
            o["device"] = self.device
        if self.visual_importance:
            o["visual_importance"] = True
        return o


def register():
    bpy.utils.register_class(ClppmSceneSettings)
    bpy.types.Scene.clppm = bpy.props.PointerProperty(type=ClppmSceneSettings)


def unregister():
    del bpy.types.Scene.clppm
    bpy.utils.unregister_class(ClppmSceneSettings)

"""The render properties panel of the CLPPM engine, and the material, light, world and camera
panels of Blender's own engines shown for it too (the exporter reads what they edit)."""
import bpy


class CLPPM_PT_render(bpy.types.Panel):
    bl_label = "clppm"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    COMPAT_ENGINES = {"CLPPM"}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        s = context.scene.clppm
        layout.prop(s, "integrator")
        col = layout.column(align=True)
        col.prop(s, "passes")
        col.prop(s, "time")
        col.prop(s, "target_error")
        col = layout.column(align=True)
        col.prop(s, "photons")
        col.prop(s, "alpha")
        col.prop(s, "visual_importance")
        layout.prop(s, "device")
        layout.prop(s, "seed")
        layout.prop(s, "update_every")


def _borrowed_panels():
    for panel in bpy.types.Panel.__subclasses__():
        engines = getattr(panel, "COMPAT_ENGINES", None)
        if engines is not None and "BLENDER_EEVEE" in engines and panel.__name__ != "CLPPM_PT_render":
            yield panel


def register():
    bpy.utils.register_class(CLPPM_PT_render)
    for panel in _borrowed_panels():
        panel.COMPAT_ENGINES.add("CLPPM")


def unregister():
    for panel in _borrowed_panels():
        panel.COMPAT_ENGINES.discard("CLPPM")
    bpy.utils.unregister_class(CLPPM_PT_render)

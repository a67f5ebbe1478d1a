"""clppm for Blender: a render engine that renders the scene through clppm (progressive photon
mapping on OpenCL), with its area lights, world and depth of field. See docs/blender.md, "Blender"."""

bl_info = {
    "name": "clppm",
    "author": "clppm",
    "version": (0, 1, 0),
    "blender": (4, 2, 0),
    "location": "Properties > Render > Render Engine",
    "description": "Render through clppm, progressive photon mapping on OpenCL",
    "category": "Render",
}

import bpy  # noqa: E402

from . import engine, properties, ui  # noqa: E402


class ClppmPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    clppm_path: bpy.props.StringProperty(
        name="clppm", subtype="FILE_PATH", default="",
        description="A clppm command, or a folder holding the clppm Python package (empty: the CLPPM environment "
                    "variable, the clppm Python module, or clppm on PATH)")

    def draw(self, context):
        self.layout.prop(self, "clppm_path")


def register():
    bpy.utils.register_class(ClppmPreferences)
    properties.register()
    bpy.utils.register_class(engine.ClppmRenderEngine)
    ui.register()


def unregister():
    ui.unregister()
    bpy.utils.unregister_class(engine.ClppmRenderEngine)
    properties.unregister()
    bpy.utils.unregister_class(ClppmPreferences)

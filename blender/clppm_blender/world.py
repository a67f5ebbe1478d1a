"""The Blender world as clppm's environment options (clppm has no world node tree; glTF no world).

Read: a world without nodes (its colour), or a Background node at the world output, whose Color
is a constant or an Environment Texture (an .hdr or .exr file, equirectangular) optionally turned
about Z by a Mapping node, times its Strength. Anything else in the tree is reported as not
supported and the world is read as its Background colour.

Axes. Blender's equirectangular images put their centre at world +X and their top at +Z (Cycles'
direction_to_equirectangular); clppm's (docs/scenes.md, "Environment") put the centre at glTF's -Z, which
is Blender's +Y, with u running the same way round. Turning clppm's map by -90 degrees about the
up axis brings its centre to +X; a Mapping node's Z rotation turns the lookup, so the picture
turns the other way.
"""
import math
import os

import bpy

HDR_SUFFIXES = (".hdr", ".exr")


def _linked_node(socket):
    return socket.links[0].from_node if socket.is_linked else None


BLACK = {"no_default_light": True}  # no environment, and no white world for a scene without lights


def _color(rgb, strength=1.0):
    if max(rgb) * strength <= 0.0:
        return dict(BLACK)
    return {"env_color": tuple(rgb), "env_strength": strength}


def environment_options(world, warn):
    """{env, env_color, env_strength, env_rotate} for clppm.Renderer; `warn(message)` reports
    what cannot be carried over. A scene without a world, or with a black one, renders against
    black, as in Cycles."""
    if world is None:
        return dict(BLACK)
    if not world.use_nodes or world.node_tree is None:
        return _color(tuple(world.color))
    output = next((n for n in world.node_tree.nodes if n.type == "OUTPUT_WORLD" and n.is_active_output), None)
    background = _linked_node(output.inputs["Surface"]) if output else None
    if background is None:
        return dict(BLACK)
    if background.type != "BACKGROUND":
        warn("world: only a Background shader is supported (found %s); rendering against black" % background.type)
        return dict(BLACK)
    strength = background.inputs["Strength"].default_value
    if background.inputs["Strength"].is_linked:
        warn("world: a linked Strength is not supported; using %g" % strength)
    color_in = background.inputs["Color"]
    source = _linked_node(color_in)
    if source is None:
        return _color(tuple(color_in.default_value[:3]), strength)
    if source.type == "TEX_ENVIRONMENT" and source.image is not None:
        path = bpy.path.abspath(source.image.filepath, library=source.image.library)
        if source.projection != "EQUIRECTANGULAR":
            warn("world: only equirectangular environment textures are supported (%s)" % source.projection)
        elif source.image.packed_file is not None or not path.lower().endswith(HDR_SUFFIXES) or not os.path.isfile(path):
            warn("world: the environment texture must be an .hdr or .exr file on disk (%s)" % (path or source.image.name))
        else:
            rotation = 0.0
            mapping = _linked_node(source.inputs["Vector"])
            if mapping is not None and mapping.type == "MAPPING":
                rotation = mapping.inputs["Rotation"].default_value[2]
                if abs(mapping.inputs["Rotation"].default_value[0]) + abs(mapping.inputs["Rotation"].default_value[1]) > 1e-6:
                    warn("world: the Mapping node's X and Y rotations are not supported; only Z is used")
            return {"env": path, "env_strength": strength, "env_rotate": -90.0 - math.degrees(rotation)}
    else:
        warn("world: the Background's Color comes from a %s node, which is not supported; using its "
             "default colour" % source.type)
    return _color(tuple(color_in.default_value[:3]), strength)

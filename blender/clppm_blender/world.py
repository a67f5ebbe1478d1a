"""The Blender world as clppm's environment and medium options (clppm has no world node tree; glTF
no world).

Read: a world without nodes (its colour), or a Background node at the world output, whose Color
is a constant or an Environment Texture (an .hdr or .exr file, equirectangular) optionally turned
about Z by a Mapping node, times its Strength. Anything else in the tree is reported as not
supported and the world is read as its Background colour. The world's Volume (Volume Scatter,
Volume Absorption, Principled Volume, or an Add Shader of them, with constant inputs) is clppm's
world medium.

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


def _volume_coefficients(node, warn, out):
    """Adds a volume shader's scattering and absorption per unit length (Cycles' definitions) to
    out = {"sigma_s": [r, g, b], "sigma_a": [r, g, b], "g": [anisotropies]}; False where the node is
    not one clppm renders."""
    def value(name):
        if node.inputs[name].is_linked:
            warn("world volume: a linked %s is not supported; using its value" % name)
        v = node.inputs[name].default_value
        return list(v[:3]) if hasattr(v, "__len__") else float(v)

    if node.type == "ADD_SHADER":
        ok = True
        for socket in node.inputs:
            child = _linked_node(socket)
            ok = ok and (child is None or _volume_coefficients(child, warn, out))
        return ok
    if node.type == "VOLUME_SCATTER":
        if getattr(node, "phase", "HENYEY_GREENSTEIN") != "HENYEY_GREENSTEIN":
            warn("world volume: only the Henyey-Greenstein phase function is supported (found %s)" % node.phase)
        color, density = value("Color"), max(value("Density"), 0.0)
        out["sigma_s"] = [s + max(c, 0.0) * density for s, c in zip(out["sigma_s"], color)]
        out["g"].append(value("Anisotropy"))
        return True
    if node.type == "VOLUME_ABSORPTION":
        color, density = value("Color"), max(value("Density"), 0.0)
        out["sigma_a"] = [a + max(1.0 - c, 0.0) * density for a, c in zip(out["sigma_a"], color)]
        return True
    if node.type == "PRINCIPLED_VOLUME":
        # Cycles' svm_node_principled_volume: scattering color x density, extinction (color +
        # (1 - color)(1 - sqrt(absorption color))) x density.
        color, density = value("Color"), max(value("Density"), 0.0)
        absorb = value("Absorption Color")
        if value("Emission Strength") > 0.0 or value("Blackbody Intensity") > 0.0:
            warn("world volume: emission is not supported; rendered without it")
        out["sigma_s"] = [s + max(c, 0.0) * density for s, c in zip(out["sigma_s"], color)]
        out["sigma_a"] = [a + max(1.0 - c, 0.0) * max(1.0 - math.sqrt(max(k, 0.0)), 0.0) * density
                          for a, c, k in zip(out["sigma_a"], color, absorb)]
        out["g"].append(value("Anisotropy"))
        return True
    warn("world volume: a %s node is not supported (Volume Scatter, Volume Absorption, Principled Volume "
         "and Add Shader of them are); rendering without a medium" % node.type)
    return False


def medium_options(world, warn):
    """{medium_density, medium_albedo, medium_anisotropy} for clppm.Renderer from the world's
    Volume (homogeneous: clppm's world medium, docs/blender.md), or {} for none. Blender's
    densities are per metre, as the glTF exporter's units."""
    if world is None or not world.use_nodes or world.node_tree is None:
        return {}
    output = next((n for n in world.node_tree.nodes if n.type == "OUTPUT_WORLD" and n.is_active_output), None)
    volume = _linked_node(output.inputs["Volume"]) if output else None
    if volume is None:
        return {}
    out = {"sigma_s": [0.0] * 3, "sigma_a": [0.0] * 3, "g": []}
    if not _volume_coefficients(volume, warn, out):
        return {}
    if len(out["g"]) > 1:
        warn("world volume: one scattering shader is supported; their anisotropies are averaged")
    density = [s + a for s, a in zip(out["sigma_s"], out["sigma_a"])]
    if max(density) <= 0.0:
        return {}
    albedo = [min(s / d, 1.0) if d > 0 else 1.0 for s, d in zip(out["sigma_s"], density)]
    g = sum(out["g"]) / len(out["g"]) if out["g"] else 0.0
    return {"medium_density": tuple(density), "medium_albedo": tuple(albedo),
            "medium_anisotropy": min(max(g, -0.999), 0.999)}

#!/usr/bin/env python3
"""Renders a glTF file with Blender's Cycles as an independent reference for clppm, offline (not in
CI, not a dependency): the file imported by Blender's own glTF importer, seen through its first
camera or, without one, through clppm's default view (from +Z at the bounding sphere's distance
r / sin(0.4) x 1.05, vertical field of view 0.8 rad), lit by the file's lights and by a world of
colour (1, 1, 1) at the given strength (clppm's default environment; 0 for none), the file's
punctual lights taken one for one as clppm takes them; the material extensions Blender's importer
does not read are set by hand (patch_unimported_extensions). Box pixel
filter, as clppm's uniform jitter; 16 bounces of every kind; no clamping. Writes linear EXR.

    python3 -m venv /tmp/bpyenv && /tmp/bpyenv/bin/pip install bpy
    /tmp/bpyenv/bin/python bench/cycles_reference.py SCENE.glb OUT.exr [--size 256] [--spp 1024]
        [--world 1.0]
"""
import argparse
import json
import math
import os
import struct
import sys
import urllib.parse

import bpy
from mathutils import Vector


def gltf_json(path):
    """The glTF's JSON, from a .gltf or a .glb's first chunk."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] == b"glTF":
        n = struct.unpack_from("<I", data, 12)[0]
        return json.loads(data[20:20 + n])
    return json.loads(data)


def irid_texture_input(path, doc, nodes, links, info, channel):
    """An output socket giving channel (R or G) of the glTF texture `info` (a textureInfo) at the
    mesh's first UV map, or None without one. Textures of a .glb, on another UV set or with
    KHR_texture_transform are not read (a warning, and None)."""
    if not info:
        return None
    tex = doc["textures"][info["index"]]
    image = doc["images"][tex["source"]]
    if "uri" not in image or info.get("texCoord", 0) != 0 or "extensions" in info:
        print("warning: iridescence texture not read (embedded, another UV set or transformed)")
        return None
    node = nodes.new("ShaderNodeTexImage")
    node.image = bpy.data.images.load(os.path.join(os.path.dirname(os.path.abspath(path)),
                                                   urllib.parse.unquote(image["uri"])), check_existing=True)
    node.image.colorspace_settings.name = "Non-Color"
    sep = nodes.new("ShaderNodeSeparateColor")
    links.new(node.outputs["Color"], sep.inputs["Color"])
    return sep.outputs["Red" if channel == "R" else "Green"]


def patch_anisotropy(aniso, pbr, nodes, links):
    """KHR_materials_anisotropy on Cycles' Principled BSDF. Blender's importer sets Anisotropic to the
    strength, keeps the roughness and leaves the tangent to Cycles' default; Cycles stretches by
    aspect = sqrt(1 - 0.9 A), alpha_x = r^2 / aspect along the tangent, alpha_y = r^2 aspect. The
    extension wants alpha_t = mix(r^2, 1, strength^2) along the direction (the UV tangent turned by
    anisotropyRotation) and alpha_b = r^2 across (at least 0.001, as clppm keeps it): so r^2 =
    sqrt(alpha_t alpha_b), A = (1 - alpha_b / alpha_t) / 0.9. Cycles reaches a stretch of 10 at
    most; beyond it (roughness 0 at any strength) alpha_t is kept and the lobe is wider across
    (a warning)."""
    rough = pbr.inputs["Roughness"]
    if rough.is_linked or "anisotropyTexture" in aniso:
        print("warning: textured roughness or anisotropy left as Blender's importer set it")
        return
    r2 = rough.default_value ** 2
    s = aniso.get("anisotropyStrength", 0.0)
    alpha_b, alpha_t = max(r2, 1e-3), r2 + (1 - r2) * s * s
    alpha_t = max(alpha_t, alpha_b)
    ratio = alpha_b / alpha_t
    if ratio < 0.1:
        print("warning: a stretch of %.0f; Cycles reaches 10" % (1 / ratio))
        ratio = 0.1
    aspect = math.sqrt(ratio)
    rough.default_value = math.sqrt(alpha_t * aspect)
    pbr.inputs["Anisotropic"].default_value = (1 - ratio) / 0.9
    pbr.inputs["Anisotropic Rotation"].default_value = aniso.get("anisotropyRotation", 0.0) / (2 * math.pi)
    tangent = nodes.new("ShaderNodeTangent")
    tangent.direction_type = "UV_MAP"
    links.new(tangent.outputs["Tangent"], pbr.inputs["Tangent"])


def patch_unimported_extensions(path):
    """Two material extensions Blender 5.0's importer does not read, set by hand on the material
    it made, as Cycles models them: KHR_materials_iridescence as the Principled BSDF's thin film
    (index iridescenceIor, thickness iridescenceThicknessMaximum or, with
    iridescenceThicknessTexture, from the minimum to the maximum by its G; a factor other than 1
    or iridescenceTexture as a Mix Shader of the material without the film and with it by factor
    times the texture's R: irid_texture_input), and KHR_materials_diffuse_transmission as a Mix Shader of the Principled
    BSDF and a Translucent BSDF of the transmission colour by diffuseTransmissionFactor (exact for
    a material without a specular layer, specularFactor 0; otherwise the layer is mixed down too)."""
    doc = gltf_json(path)
    for i, m in enumerate(doc.get("materials", [])):
        ext = m.get("extensions", {})
        irid = ext.get("KHR_materials_iridescence")
        dt = ext.get("KHR_materials_diffuse_transmission")
        aniso = ext.get("KHR_materials_anisotropy")
        if not irid and not dt and not aniso:
            continue
        mat = bpy.data.materials.get(m.get("name", "Material_%d" % i))
        if mat is None or not mat.use_nodes:
            print("warning: no Blender material for glTF material", i)
            continue
        nodes, links = mat.node_tree.nodes, mat.node_tree.links
        pbr = next(n for n in nodes if n.type == "BSDF_PRINCIPLED")
        if aniso:
            patch_anisotropy(aniso, pbr, nodes, links)
        if irid:
            pbr.inputs["Thin Film IOR"].default_value = irid.get("iridescenceIor", 1.3)
            hi = irid.get("iridescenceThicknessMaximum", 400.0)
            thick = irid_texture_input(path, doc, nodes, links, irid.get("iridescenceThicknessTexture"), "G")
            if thick is None:
                pbr.inputs["Thin Film Thickness"].default_value = hi
            else:
                lo = irid.get("iridescenceThicknessMinimum", 100.0)
                ramp = nodes.new("ShaderNodeMath")
                ramp.operation = "MULTIPLY_ADD"  # lo + (hi - lo) g
                links.new(thick, ramp.inputs[0])
                ramp.inputs[1].default_value, ramp.inputs[2].default_value = hi - lo, lo
                links.new(ramp.outputs["Value"], pbr.inputs["Thin Film Thickness"])
            factor = irid.get("iridescenceFactor", 0.0)
            weight = irid_texture_input(path, doc, nodes, links, irid.get("iridescenceTexture"), "R")
            if factor != 1.0 or weight is not None:
                bare = nodes.new("ShaderNodeBsdfPrincipled")  # the same material without the film
                for inp, copy in zip(pbr.inputs, bare.inputs):
                    if inp.is_linked:
                        links.new(inp.links[0].from_socket, copy)
                    elif hasattr(inp, "default_value"):
                        copy.default_value = inp.default_value
                bare.inputs["Thin Film Thickness"].default_value = 0.0
                if bare.inputs["Thin Film Thickness"].is_linked:
                    links.remove(bare.inputs["Thin Film Thickness"].links[0])
                for attr in ("distribution", "subsurface_method"):
                    setattr(bare, attr, getattr(pbr, attr))
                mix = nodes.new("ShaderNodeMixShader")
                targets = [lk.to_socket for lk in pbr.outputs["BSDF"].links]
                if weight is None:
                    mix.inputs["Fac"].default_value = factor
                else:
                    scale = nodes.new("ShaderNodeMath")
                    scale.operation = "MULTIPLY"
                    links.new(weight, scale.inputs[0])
                    scale.inputs[1].default_value = factor
                    links.new(scale.outputs["Value"], mix.inputs["Fac"])
                links.new(bare.outputs["BSDF"], mix.inputs[1])
                links.new(pbr.outputs["BSDF"], mix.inputs[2])
                for t in targets:
                    links.new(mix.outputs["Shader"], t)
        if dt:
            if ext.get("KHR_materials_specular", {}).get("specularFactor", 1.0) != 0.0:
                print("warning: diffuse transmission under a specular layer mixes the layer down too")
            out = next(n for n in nodes if n.type == "OUTPUT_MATERIAL")
            tl = nodes.new("ShaderNodeBsdfTranslucent")
            c = dt.get("diffuseTransmissionColorFactor", [1.0, 1.0, 1.0])
            tl.inputs["Color"].default_value = (c[0], c[1], c[2], 1.0)
            mix = nodes.new("ShaderNodeMixShader")
            mix.inputs["Fac"].default_value = dt.get("diffuseTransmissionFactor", 0.0)
            links.new(pbr.outputs["BSDF"], mix.inputs[1])
            links.new(tl.outputs["BSDF"], mix.inputs[2])
            links.new(mix.outputs["Shader"], out.inputs["Surface"])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("out")
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--world", type=float, default=1.0)
    # Single-scattering GGX in every Principled BSDF (Cycles' default is its multiscatter GGX):
    # to measure how much of a difference multiple scattering on the microsurface makes.
    ap.add_argument("--single-scatter", action="store_true")
    a = ap.parse_args(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:])

    bpy.ops.wm.read_factory_settings(use_empty=True)
    # RAW: KHR_lights_punctual values read one for one (lux as W/m^2), as clppm reads them
    # (docs/scenes.md, "Punctual lights"); Blender's default would divide by 683 lm/W.
    bpy.ops.import_scene.gltf(filepath=a.scene, export_import_convert_lighting_mode="RAW")
    scene = bpy.context.scene
    # The importer draws bones with a mesh of its own (an icosphere of radius 1 at the origin),
    # linked into the scene: invisible among the figure's cards yet casting shadows in Cycles (it
    # made the Stip figure 9% darker under a sun than the file says). It is not in the file: out.
    shapes = {pb.custom_shape for o in scene.objects if o.type == "ARMATURE" for pb in o.pose.bones if pb.custom_shape}
    for o in shapes:
        bpy.data.objects.remove(o)
    patch_unimported_extensions(a.scene)
    if a.single_scatter:
        for mat in bpy.data.materials:
            for n in (mat.node_tree.nodes if mat.node_tree else []):
                if n.type == "BSDF_PRINCIPLED":
                    n.distribution = "GGX"
    # KHR_lights_punctual's lights are points and parallel light; Blender's importer gives a sun
    # its default angle of 0.53 degrees, which puts a glint of the sun's disc on every mirror
    # that the file's parallel light cannot (bench/RESULTS.md, issue 62, measures it). The
    # file's light, as clppm renders it.
    for o in scene.objects:
        if o.type == "LIGHT":
            if o.data.type == "SUN":
                o.data.angle = 0.0
            else:
                o.data.shadow_soft_size = 0.0
    cams = [o for o in scene.objects if o.type == "CAMERA"]
    if cams:
        scene.camera = cams[0]
    else:
        # Evaluated meshes: skinned ones as drawn (clppm's bounds are those of what it renders).
        depsgraph = bpy.context.evaluated_depsgraph_get()
        pts = []
        for o in scene.objects:
            if o.type == "MESH":
                eo = o.evaluated_get(depsgraph)
                pts += [eo.matrix_world @ Vector(v.co) for v in eo.to_mesh().vertices]
        lo = Vector((min(p[i] for p in pts) for i in range(3)))
        hi = Vector((max(p[i] for p in pts) for i in range(3)))
        c, r = (lo + hi) / 2, (hi - lo).length / 2
        d = r / math.sin(0.4) * 1.05
        cam_data = bpy.data.cameras.new("default")
        cam_data.sensor_fit = "VERTICAL"
        cam_data.angle_y = 0.8
        cam_data.clip_start, cam_data.clip_end = d * 1e-3, d * 10
        cam = bpy.data.objects.new("default", cam_data)
        scene.collection.objects.link(cam)
        # glTF +Z is Blender -Y: from -Y towards +Y, up +Z.
        cam.location = (c.x, c.y - d, c.z)
        cam.rotation_euler = (math.pi / 2, 0, 0)
        scene.camera = cam
    world = bpy.data.worlds.new("white")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (1, 1, 1, 1)
    bg.inputs["Strength"].default_value = a.world
    scene.world = world
    scene.render.engine = "CYCLES"
    cy = scene.cycles
    cy.device = "CPU"
    cy.samples = a.spp
    cy.use_adaptive_sampling = False
    cy.use_denoising = False
    cy.max_bounces = cy.diffuse_bounces = cy.glossy_bounces = cy.transmission_bounces = 16
    cy.transparent_max_bounces = 16
    cy.caustics_reflective = cy.caustics_refractive = True
    cy.sample_clamp_direct = cy.sample_clamp_indirect = 0.0
    cy.blur_glossy = 0.0
    cy.pixel_filter_type = "BOX"
    cy.filter_width = 1.0
    scene.render.resolution_x = scene.render.resolution_y = a.size
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = a.out
    bpy.ops.render.render(write_still=True)
    print("wrote", a.out)


if __name__ == "__main__":
    main()

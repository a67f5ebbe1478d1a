"""A Blender scene as what clppm renders: a glTF file written by Blender's own exporter (materials,
textures, cameras, punctual lights), the area lights appended to it as emissive geometry
(area_lights.py), and the options for what glTF does not carry: the world (world.py), the
camera's depth of field, the resolution, and which camera to look through.

Light units: the exporter's 'COMPAT' lighting mode writes a point or spot light of P watts as
P / (4 pi) W/sr and a sun of E W/m^2 as E, which clppm reads one for one (README, "Punctual
lights"): the radiometric values Cycles renders with.
"""
import json
import math
import os

import bpy

from . import area_lights, main_thread
from .world import environment_options, medium_options


def _camera_index(gltf, camera_object):
    for node in gltf.get("nodes", []):
        if node.get("name") == camera_object.name and "camera" in node:
            return node["camera"]
    return None


def _area_light(obj, warn):
    light = obj.data
    m = obj.matrix_world
    sx, sy = m.col[0].xyz.length, m.col[1].xyz.length
    points = area_lights.outline(light.shape, light.size, light.size_y)
    area = area_lights.polygon_area(points) * sx * sy
    power = light.energy * 2.0 ** getattr(light, "exposure", 0.0)
    if not getattr(light, "normalize", True):
        power *= area
    spread = math.degrees(light.spread)  # Cycles' soft-box spread, power kept (docs/blender.md, "Blender")
    color = list(light.color)
    if getattr(light, "use_temperature", False):
        color = [c * t for c, t in zip(color, light.temperature_color)]
    return {"name": obj.name, "points": points, "radiance": area_lights.radiance(power, area), "color": color,
            "matrix": area_lights.gltf_matrix(m), "spread": min(180.0, max(spread, 0.01))}


def _solid_glass(gltf):
    """Cycles' glass is solid (it refracts where light enters and where it leaves); glTF's
    transmission without KHR_materials_volume is a thin wall, and the exporter writes a volume only
    where the glTF Material Output node gives a thickness. Every transmissive material without one
    gets a volume (thicknessFactor 1: the mesh is closed), as Blender renders it."""
    for m in gltf.get("materials", []):
        ext = m.setdefault("extensions", {})
        if "KHR_materials_transmission" in ext and "KHR_materials_volume" not in ext:
            ext["KHR_materials_volume"] = {"thicknessFactor": 1.0}
            used = gltf.setdefault("extensionsUsed", [])
            if "KHR_materials_volume" not in used:
                used.append("KHR_materials_volume")


def _other_lights(obj, warn):
    light = obj.data
    if light.type in ("POINT", "SPOT") and light.shadow_soft_size > 0:
        warn("%s light %s: a radius of %g is not supported; it is a point" % (light.type.lower(), obj.name,
                                                                           light.shadow_soft_size))
    if light.type == "SUN" and light.angle > 1e-4:
        warn("sun %s: an angle of %.2f degrees is not supported; its light is parallel" % (obj.name,
                                                                                      math.degrees(light.angle)))


def spot_inner_cone(spot_size, blend):
    """glTF's inner cone angle for a Cycles spot light of full angle `spot_size` and `blend`.

    Cycles ramps a spot's edge with a smoothstep in cos(angle) from the cone's edge c0 = cos(spot_size/2)
    over w = (1 - c0) blend; glTF (and clppm) ramp linearly in cos from the outer to the inner
    cone and square it. The exporter's inner angle, (spot_size/2)(1 - blend), gives a different
    power (0.79x Cycles' at blend 0.3). The inner cone at c1 = c0 + 3w/4 keeps the power: the
    smoothstep's integral over its ramp is w/2, the squared ramp's (c1 - c0)/3, and the solid
    angle is d(cos) d(phi), so the light emits what Cycles' does, with a slightly different edge."""
    c0 = math.cos(0.5 * spot_size)
    c1 = min(1.0, c0 + 0.75 * (1.0 - c0) * blend)
    return math.acos(c1)


def _spot_cones(gltf, depsgraph):
    lights = gltf.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    by_name = {l.get("name"): l for l in lights if l.get("type") == "spot"}
    for instance in depsgraph.object_instances:
        light = instance.object.data if instance.object.type == "LIGHT" else None
        if light is not None and light.type == "SPOT" and light.name in by_name:
            spot = by_name[light.name].setdefault("spot", {})
            spot["outerConeAngle"] = 0.5 * light.spot_size
            spot["innerConeAngle"] = spot_inner_cone(light.spot_size, light.spot_blend)


def _depth_of_field(scene, camera):
    cam = camera.data
    if not cam.dof.use_dof:
        return {}
    unit = scene.unit_settings.scale_length or 1.0
    aperture = (cam.lens * 1e-3) / (2.0 * cam.dof.aperture_fstop) / unit
    if cam.dof.focus_object is not None:
        forward = -camera.matrix_world.col[2].xyz.normalized()
        target = cam.dof.focus_object.matrix_world.translation
        distance = (target - camera.matrix_world.translation).dot(forward)
    else:
        distance = cam.dof.focus_distance
    options = {"aperture": aperture}
    if distance > 0:
        options["focus_distance"] = distance
    return options


GLTF_OPTIONS = {"check_existing": False, "export_format": "GLTF_SEPARATE", "export_cameras": True,
                "export_lights": True, "export_yup": True, "export_apply": True,
                "export_import_convert_lighting_mode": "COMPAT", "export_extras": False, "use_renderable": True}


def _write_gltf(path, warn):
    known = bpy.ops.export_scene.gltf.get_rna_type().properties.keys()
    if "export_import_convert_lighting_mode" not in known:  # Blender before 3.6
        warn("this Blender's glTF exporter has no lighting mode: point, spot and sun lights are as it writes them")
    bpy.ops.export_scene.gltf(filepath=path, **{k: v for k, v in GLTF_OPTIONS.items() if k in known})


def export(depsgraph, directory, warn, cancelled=lambda: False):
    """Writes directory/scene.gltf for `depsgraph`'s scene and returns (path, options). The glTF
    exporter is an operator, which runs only on Blender's main thread (main_thread.py); the rest
    reads the depsgraph, on any thread."""
    scene = depsgraph.scene
    if scene.camera is None:
        raise RuntimeError("the scene has no camera")
    path = os.path.join(directory, "scene.gltf")
    main_thread.call(lambda: _write_gltf(path, warn), cancelled)
    with open(path) as f:
        gltf = json.load(f)
    lights = []
    for instance in depsgraph.object_instances:
        obj = instance.object
        if obj.type != "LIGHT":
            continue
        if obj.data.type == "AREA":
            lights.append(_area_light(obj, warn))
        else:
            _other_lights(obj, warn)
    area_lights.append(gltf, lights)
    _spot_cones(gltf, depsgraph)
    _solid_glass(gltf)
    with open(path, "w") as f:
        json.dump(gltf, f)
    camera = _camera_index(gltf, scene.camera)
    if camera is None:
        raise RuntimeError("the exporter wrote no camera for %s" % scene.camera.name)
    r = scene.render
    options = {
        "camera": camera,
        "width": max(1, int(r.resolution_x * r.resolution_percentage / 100)),
        "height": max(1, int(r.resolution_y * r.resolution_percentage / 100)),
    }
    options.update(_depth_of_field(scene, scene.camera))
    options.update(environment_options(scene.world, warn))
    options.update(medium_options(scene.world, warn))
    return path, options

"""Scenes built by script for the add-on's tests, and renders of them by Cycles and by clppm."""
import math

import bpy
import numpy as np

SIZE = 96


def clear():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.resolution_x = scene.render.resolution_y = SIZE
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.view_settings.view_transform = "Standard"
    return scene


def material(name, color, roughness=1.0, metallic=0.0, transmission=0.0, ior=1.5, specular=0.0):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    p = m.node_tree.nodes["Principled BSDF"]
    p.inputs["Base Color"].default_value = (*color, 1.0)
    p.inputs["Roughness"].default_value = roughness
    p.inputs["Metallic"].default_value = metallic
    p.inputs["Transmission Weight"].default_value = transmission
    p.inputs["IOR"].default_value = ior
    p.inputs["Specular IOR Level"].default_value = specular
    return m


def add(obj, mat):
    obj.data.materials.append(mat)
    return obj


def camera(location, target, lens=35.0):
    bpy.ops.object.camera_add(location=location)
    cam = bpy.context.object
    direction = (np.array(target) - np.array(location))
    cam.rotation_euler = _look(direction)
    cam.data.lens = lens
    bpy.context.scene.camera = cam
    return cam


def _look(direction):
    from mathutils import Vector
    return Vector(direction).to_track_quat("-Z", "Y").to_euler()


def area_light(location, target, power, shape="RECTANGLE", size=1.0, size_y=0.5):
    bpy.ops.object.light_add(type="AREA", location=location)
    light = bpy.context.object
    light.rotation_euler = _look(np.array(target) - np.array(location))
    light.data.energy = power
    light.data.shape = shape
    light.data.size = size
    light.data.size_y = size_y
    return light


def world(color=None, strength=1.0, image=None, rotation=0.0):
    w = bpy.data.worlds.new("World")
    w.use_nodes = True
    bg = w.node_tree.nodes["Background"]
    bg.inputs["Strength"].default_value = strength
    if color is not None:
        bg.inputs["Color"].default_value = (*color, 1.0)
    if image is not None:
        tex = w.node_tree.nodes.new("ShaderNodeTexEnvironment")
        tex.image = bpy.data.images.load(image)
        w.node_tree.links.new(tex.outputs["Color"], bg.inputs["Color"])
        if rotation:
            coords = w.node_tree.nodes.new("ShaderNodeTexCoord")
            mapping = w.node_tree.nodes.new("ShaderNodeMapping")
            mapping.inputs["Rotation"].default_value[2] = rotation
            w.node_tree.links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
            w.node_tree.links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
    bpy.context.scene.world = w
    return w


def room_objects():
    """A grey floor, a red cube and a grey sphere."""
    grey = material("grey", (0.6, 0.6, 0.6))
    red = material("red", (0.7, 0.15, 0.1))
    bpy.ops.mesh.primitive_plane_add(size=8)
    add(bpy.context.object, grey)
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(-0.8, 0.2, 0.5))
    add(bpy.context.object, red)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.6, location=(0.8, -0.2, 0.6), segments=48, ring_count=24)
    bpy.ops.object.shade_smooth()
    add(bpy.context.object, grey)


def diffuse_room():
    """Diffuse objects on a floor, an area light, a grey world (issue 34's first comparison)."""
    scene = clear()
    room_objects()
    area_light((0.0, -1.0, 3.0), (0.0, 0.0, 0.0), 300.0)
    camera((0.0, -6.0, 3.5), (0.0, 0.0, 0.4))
    world((0.2, 0.2, 0.2))
    return scene


def fog_room():
    """The diffuse room's objects under a point light and an area light, against black, in a world
    volume: a Volume Scatter (density 0.12, colour 0.9, 0.8, 0.7, anisotropy 0.3) plus a Volume
    Absorption (density 0.03, colour 0.5): clppm's world medium against Cycles' world volume."""
    scene = clear()
    room_objects()
    bpy.ops.object.light_add(type="POINT", location=(1.5, -1.0, 2.0))
    bpy.context.object.data.energy = 400.0
    bpy.context.object.data.shadow_soft_size = 0.0
    area_light((-1.0, -1.0, 3.0), (0.0, 0.0, 0.0), 200.0)
    camera((0.0, -6.0, 3.0), (0.0, 0.0, 0.4))
    w = world((0.0, 0.0, 0.0))
    nodes, links = w.node_tree.nodes, w.node_tree.links
    scatter = nodes.new("ShaderNodeVolumeScatter")
    scatter.inputs["Color"].default_value = (0.9, 0.8, 0.7, 1.0)
    scatter.inputs["Density"].default_value = 0.12
    scatter.inputs["Anisotropy"].default_value = 0.3
    absorb = nodes.new("ShaderNodeVolumeAbsorption")
    absorb.inputs["Color"].default_value = (0.5, 0.5, 0.5, 1.0)
    absorb.inputs["Density"].default_value = 0.03
    add_shader = nodes.new("ShaderNodeAddShader")
    links.new(scatter.outputs[0], add_shader.inputs[0])
    links.new(absorb.outputs[0], add_shader.inputs[1])
    links.new(add_shader.outputs[0], nodes["World Output"].inputs["Volume"])
    return scene


def punctual_lights():
    """The diffuse room's objects under a point light, a spot light with a soft edge and a sun,
    against black: the exporter's light units and clppm's spot falloff against Cycles'."""
    scene = clear()
    room_objects()
    for kind, location, energy in (("POINT", (-2.0, -1.0, 2.0), 150.0), ("SPOT", (1.0, -1.5, 3.0), 500.0),
                                   ("SUN", (0.0, 0.0, 5.0), 1.0)):
        bpy.ops.object.light_add(type=kind, location=location)
        light = bpy.context.object
        light.rotation_euler = _look(np.array((0.3, 0.2, 0.0)) - np.array(location))
        light.data.energy = energy
        if kind == "SUN":
            light.data.angle = 0.0
        else:
            light.data.shadow_soft_size = 0.0
        if kind == "SPOT":
            light.data.spot_size, light.data.spot_blend = math.radians(70), 0.3
    camera((0.0, -6.0, 3.5), (0.0, 0.0, 0.4))
    world((0.0, 0.0, 0.0))
    return scene


def glass_on_floor():
    """A glass sphere on a floor under an area light: the caustic."""
    scene = clear()
    bpy.ops.mesh.primitive_plane_add(size=8)
    add(bpy.context.object, material("floor", (0.7, 0.7, 0.7)))
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.7, location=(0.0, 0.0, 0.7), segments=64, ring_count=32)
    bpy.ops.object.shade_smooth()
    add(bpy.context.object, material("glass", (1.0, 1.0, 1.0), roughness=0.0, transmission=1.0, ior=1.5,
                                     specular=0.5))
    area_light((0.0, 0.0, 4.0), (0.0, 0.0, 0.0), 200.0, shape="SQUARE", size=0.5)
    camera((0.0, -5.0, 3.0), (0.0, 0.0, 0.3))
    world((0.0, 0.0, 0.0))
    return scene


def render(engine, path, samples=1024, **settings):
    """Renders the current scene with `engine` and returns its image as float32 (H, W, 3), top row
    first; Cycles with `samples` samples, caustics on; CLPPM with the given scene.clppm settings."""
    scene = bpy.context.scene
    scene.render.engine = engine
    if engine == "CYCLES":
        scene.cycles.device = "CPU"
        scene.cycles.samples = samples
        scene.cycles.use_adaptive_sampling = False
        scene.cycles.use_denoising = False
        scene.cycles.max_bounces = 16
        scene.cycles.diffuse_bounces = scene.cycles.glossy_bounces = 16
        scene.cycles.transmission_bounces = scene.cycles.transparent_max_bounces = 16
        scene.cycles.volume_bounces = 16
        scene.cycles.caustics_reflective = scene.cycles.caustics_refractive = True
        scene.cycles.blur_glossy = 0.0
        scene.cycles.sample_clamp_direct = scene.cycles.sample_clamp_indirect = 0.0
        scene.cycles.seed = 7
    else:
        for k, v in settings.items():
            setattr(scene.clppm, k, v)
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(path, check_existing=False)
    w, h = image.size
    px = np.empty(w * h * 4, dtype=np.float32)
    image.pixels.foreach_get(px)
    bpy.data.images.remove(image)
    return px.reshape(h, w, 4)[::-1, :, :3].copy()


def box_rel_mse(a, b, k=4):
    """Relative MSE of a against b after a k x k box filter (bias more than noise), as `clppm compare --box`."""
    h, w = (a.shape[0] // k) * k, (a.shape[1] // k) * k
    fa = a[:h, :w].reshape(h // k, k, w // k, k, 3).mean(axis=(1, 3))
    fb = b[:h, :w].reshape(h // k, k, w // k, k, 3).mean(axis=(1, 3))
    return float(np.mean((fa - fb) ** 2 / (fb ** 2 + 1e-2)))


def write_hdr(path, rgb):
    """A Radiance .hdr of float RGB (H, W, 3), top row first, flat RGBE scanlines: exact, with no
    colour management on the way (Blender's image.save() applies its view transform)."""
    h, w = rgb.shape[:2]
    m = rgb.max(axis=2)
    mant, exp = np.frexp(m)
    scale = np.where(m > 1e-32, mant * 256.0 / np.maximum(m, 1e-32), 0.0)
    rgbe = np.zeros((h, w, 4), dtype=np.uint8)
    rgbe[..., :3] = np.clip(rgb * scale[..., None], 0, 255).astype(np.uint8)
    rgbe[..., 3] = np.where(m > 1e-32, exp + 128, 0).astype(np.uint8)
    with open(path, "wb") as f:
        f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (h, w))
        f.write(rgbe.tobytes())
    return path


def sky_map(path, width=128, height=64, sun=(0.15, 0.3)):
    """An equirectangular .hdr: a dim blue-grey sky, a darker ground, and a small bright sun at
    (u, v) = `sun` (image coordinates from the top left), so that the map's orientation shows in
    the shadows."""
    v = (np.arange(height) + 0.5)[:, None] / height
    u = (np.arange(width) + 0.5)[None, :] / width
    rgb = np.zeros((height, width, 3), dtype=np.float32)
    sky = np.broadcast_to(v < 0.5, (height, width))
    rgb[..., 0] = np.where(sky, 0.25, 0.05)
    rgb[..., 1] = np.where(sky, 0.3, 0.05)
    rgb[..., 2] = np.where(sky, 0.45, 0.05)
    su, sv = sun
    spot = (np.abs(u - su) < 1.5 / width) & (np.abs(v - sv) < 1.5 / height)
    rgb[spot] = 400.0
    return write_hdr(path, rgb)


def under_the_sky(map_path, rotation=0.0):
    """Diffuse objects lit only by an environment map (turned by `rotation` radians about Z)."""
    scene = clear()
    grey = material("grey", (0.6, 0.6, 0.6))
    bpy.ops.mesh.primitive_plane_add(size=10)
    add(bpy.context.object, grey)
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0.0, 0.0, 0.5))
    add(bpy.context.object, material("blue", (0.2, 0.3, 0.7)))
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.5, location=(1.5, 1.0, 0.5), segments=48, ring_count=24)
    bpy.ops.object.shade_smooth()
    add(bpy.context.object, grey)
    camera((3.0, -5.0, 3.0), (0.3, 0.3, 0.3))
    world(image=map_path, rotation=rotation)
    return scene

#!/usr/bin/env python3
"""Renders the reference images under tests/references/ with Mitsuba 3, an independent renderer,
from the glTF scenes tests/data/make_test_gltf.py writes (reference_scenes). Run offline, not in
CI:
    python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba numpy
    /tmp/mi/bin/python tests/references/make_references.py [spp [scene ...]]
The scenes are read from the glTF files themselves (the small subset those files use:
tests/references/gltf_subset.py; mesh nodes translated and scaled, a perspective camera), so both
renderers see the same triangles. Mapping to Mitsuba: baseColorTexture is a bilinear `bitmap` (sRGB) with the sampler's wrap mode,
normalTexture a `normalmap` (linear bitmap) around the diffuse BSDF, with Mitsuba's own additions
switched off (since 3.7.1 it multiplies by the terminator shadowing of Conty Estevez et al. 2019,
which glTF does not have: with it a constant map of one tilt renders 0.927 times the same tilt
given as vertex normals, and the normal panel 4% darker than glTF's definition; and it folds
normals that face away from the geometric side, which the panel's 31-degree tilts never reach),
alphaMode MASK a `mask` whose opacity is the texture's alpha thresholded at alphaCutoff (nearest
texel); diffuse surfaces are `twosided`, as clppm's reflect on both sides; a material with
KHR_materials_transmission is `roughdielectric` (GGX, alpha = roughness^2, visible-normal
sampling) or `dielectric` at roughness 0, of the glTF ior against 1.0; KHR_materials_volume's
attenuation becomes an interior `homogeneous` medium of albedo 0 and sigma_t = -ln(colour) /
distance (integrator `volpath`); a smooth metal (metallicFactor 1, roughness 0) is a `conductor`
whose Fresnel curve follows glTF's Schlick curve from F0 = the base colour (schlick_conductor);
everything else is `diffuse` with the base colour (these scenes give diffuse surfaces
specularFactor 0) and emissive surfaces are one-sided `area` emitters of radiance emissiveFactor
times emissiveStrength. KHR_lights_punctual's directional lights are `directional` emitters of
that irradiance; the world is a `constant` emitter of the scene's clppm_environment colour, or of
radiance 1 (clppm's default white world) when the scene has none. Box pixel filter, as clppm's uniform jitter;
unbounded path length with Russian roulette.
"""
import base64
import json
import math
import os
import sys
import tempfile

import mitsuba as mi

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gltf_subset import quat_rotate, read_accessor, read_buffers, write_ply  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "data")
SCENES = ("ref_rough_glass", "ref_tinted_volume", "ref_textured", "ref_normal_panel")
SIZE = 64


def texture(doc, index, tmp, key, srgb=True, alpha_cutoff=None):
    """A glTF texture as a Mitsuba bitmap: the image's RGB (sRGB decoded by Mitsuba), or with
    alpha_cutoff its alpha thresholded (the MASK test clppm applies) as a nearest-filtered
    opacity. Wrap modes REPEAT or CLAMP_TO_EDGE and magFilter NEAREST from the sampler."""
    import numpy as np
    t = doc["textures"][index]
    img = doc["images"][t["source"]]
    data = base64.b64decode(img["uri"][img["uri"].index(",") + 1:])
    path = os.path.join(tmp, "%s.png" % key)
    open(path, "wb").write(data)
    rgba = np.array(mi.Bitmap(path))
    sampler = doc.get("samplers", [{}])[t["sampler"]] if "sampler" in t else {}
    wrap = "clamp" if sampler.get("wrapS", 10497) == 33071 else "repeat"
    if alpha_cutoff is not None:
        a = (rgba[..., 3].astype("float32") / 255.0 >= alpha_cutoff).astype("float32")
        return {"type": "bitmap", "bitmap": mi.Bitmap(a[..., None]), "raw": True, "filter_type": "nearest",
                "wrap_mode": wrap}
    bmp = mi.Bitmap(np.ascontiguousarray(rgba[..., :3]))
    bmp.set_srgb_gamma(srgb)
    filt = "nearest" if sampler.get("magFilter") == 9728 else "bilinear"
    return {"type": "bitmap", "bitmap": bmp, "raw": not srgb, "filter_type": filt, "wrap_mode": wrap}


def conductor_fresnel(eta, k, cos_i):
    """The unpolarised Fresnel reflectance of a conductor of complex index eta + i k."""
    n = complex(eta, k)
    cos_t = (1 - (1 - cos_i * cos_i) / (n * n)) ** 0.5
    rs = (cos_i - n * cos_t) / (cos_i + n * cos_t)
    rp = (n * cos_i - cos_t) / (n * cos_i + cos_t)
    return (abs(rs) ** 2 + abs(rp) ** 2) / 2


def schlick_conductor(f0):
    """(eta, k) of the conductor whose Fresnel curve is closest to Schlick's of F0 (glTF's metal):
    over eta in 0.01..2, k keeps the normal-incidence reflectance at F0, and the largest relative
    difference over incidence angles is least (0.2% for F0 = 0.95, at eta 0.08, k 2.29)."""
    assert 0 < f0 < 1, "a metal's base colour within (0, 1)"
    angles = [math.cos(math.radians(d / 10)) for d in range(0, 900, 5)]
    best = None
    for i in range(1, 200):
        eta = i * 0.01
        k2 = (f0 * (eta + 1) ** 2 - (eta - 1) ** 2) / (1 - f0)
        if k2 <= 0:
            continue
        k = math.sqrt(k2)
        err = max(abs(conductor_fresnel(eta, k, c) / (f0 + (1 - f0) * (1 - c) ** 5) - 1) for c in angles)
        if best is None or err < best[0]:
            best = (err, eta, k)
    return best[1], best[2]


def mitsuba_scene(name, tmp, size=SIZE, max_depth=-1, vertex_normals=False):
    """name: a scene of tests/data, or the path of a .gltf file (bench/peers_*.py). vertex_normals:
    shade with the file's NORMALs (as clppm does) rather than the facets' (the committed references
    were made with facet normals, on flat quads where the two are the same)."""
    path = name if name.endswith(".gltf") else os.path.join(DATA, name + ".gltf")
    name = os.path.splitext(os.path.basename(path))[0]
    doc = json.load(open(path))
    blob = read_buffers(doc, path)
    scene = {"type": "scene", "integrator": {"type": "path", "max_depth": max_depth}}
    # The world (docs/scenes.md, "Environment"): the scene's extras.clppm_environment colour, else the
    # default uniform white of radiance 1; a black one is no emitter.
    world = doc["scenes"][doc.get("scene", 0)].get("extras", {}).get("clppm_environment", {"color": [1, 1, 1]})
    assert "color" in world, "only a uniform world is mapped"
    if max(world["color"]) > 0:
        scene["world"] = {"type": "constant", "radiance": {"type": "rgb", "value": list(world["color"])}}
    # The world's medium (docs/scenes.md, "The world's medium"): Mitsuba's homogeneous medium with
    # the same extinction, albedo and Henyey-Greenstein g, where the camera is and outside every
    # transmitting shape; unbounded in both.
    world_medium = None
    fog = doc["scenes"][doc.get("scene", 0)].get("extras", {}).get("clppm_medium")
    if fog is not None:
        rgb = lambda v: list(v) if isinstance(v, list) else [v] * 3  # noqa: E731
        density, albedo = rgb(fog["density"]), rgb(fog.get("albedo", 1.0))
        top = max(density)  # Mitsuba's RGB values are at most 1: scaled
        world_medium = {"type": "homogeneous", "scale": top,
                        "sigma_t": {"type": "rgb", "value": [x / top for x in density]},
                        "albedo": {"type": "rgb", "value": albedo},
                        "phase": {"type": "hg", "g": fog.get("anisotropy", 0.0)}}
        scene["world_medium"] = world_medium
    has_medium = world_medium is not None
    mesh_nodes = 0
    for node in (doc["nodes"][i] for i in doc["scenes"][doc.get("scene", 0)]["nodes"]):
        t = node.get("translation", [0, 0, 0])
        if "camera" in node:
            q = node.get("rotation", [0, 0, 0, 1])
            fwd, up = quat_rotate(q, (0, 0, -1)), quat_rotate(q, (0, 1, 0))
            yfov = doc["cameras"][node["camera"]]["perspective"]["yfov"]
            scene["sensor"] = {
                "type": "perspective", "fov_axis": "y", "fov": math.degrees(yfov),
                "to_world": mi.ScalarTransform4f().look_at(origin=t, target=[t[i] + fwd[i] for i in range(3)], up=up),
                "film": {"type": "hdrfilm", "width": size, "height": size, "rfilter": {"type": "box"},
                         "pixel_format": "rgb"},
                "sampler": {"type": "independent"}}
            if world_medium is not None:
                scene["sensor"]["medium"] = {"type": "ref", "id": "world_medium"}
            continue
        light = node.get("extensions", {}).get("KHR_lights_punctual", {}).get("light")
        if light is not None:
            # A directional light of E lux is irradiance E in clppm's units (README.md, "Punctual
            # lights"): Mitsuba's `directional` emitter of that irradiance, along the node's -Z.
            L = doc["extensions"]["KHR_lights_punctual"]["lights"][light]
            assert L["type"] == "directional", "only directional lights are mapped"
            q = node.get("rotation", [0, 0, 0, 1])
            e = L.get("intensity", 1.0)
            scene["light_%d" % light] = {"type": "directional", "direction": list(quat_rotate(q, (0, 0, -1))),
                                         "irradiance": {"type": "rgb", "value": [c * e for c in L.get("color", [1, 1, 1])]}}
            continue
        if "mesh" not in node:
            continue
        assert "rotation" not in node, "mesh nodes are scaled and translated only"
        sc = node.get("scale", [1, 1, 1])
        tag = name if mesh_nodes == 0 else "%s_n%d" % (name, mesh_nodes)  # the first keeps the old names
        mesh_nodes += 1
        for k, prim in enumerate(doc["meshes"][node["mesh"]]["primitives"]):
            pos = read_accessor(doc, blob, prim["attributes"]["POSITION"])
            idx = read_accessor(doc, blob, prim["indices"])
            tris = [tuple(tuple(pos[idx[i + j]][c] * sc[c] + t[c] for c in range(3)) for j in range(3))
                    for i in range(0, len(idx), 3)]
            nrm = None
            if vertex_normals and "NORMAL" in prim["attributes"]:
                # Normals take the inverse transpose of the scale, then unit length.
                raw = read_accessor(doc, blob, prim["attributes"]["NORMAL"])
                unit = []
                for n in raw:
                    m = [n[c] / sc[c] for c in range(3)]
                    ln = math.sqrt(sum(x * x for x in m)) or 1.0
                    unit.append(tuple(x / ln for x in m))
                nrm = [tuple(unit[idx[i + j]] for j in range(3)) for i in range(0, len(idx), 3)]
            uvs = None
            if "TEXCOORD_0" in prim["attributes"]:
                uv = read_accessor(doc, blob, prim["attributes"]["TEXCOORD_0"])
                uvs = [tuple(uv[idx[i + j]] for j in range(3)) for i in range(0, len(idx), 3)]
            path = os.path.join(tmp, "%s_%d.ply" % (tag, k))
            write_ply(path, tris, uvs, nrm)
            m = doc["materials"][prim["material"]]
            ext = m.get("extensions", {})
            pbr = m["pbrMetallicRoughness"]
            shape = {"type": "ply", "filename": path, "face_normals": nrm is None}
            if pbr.get("metallicFactor", 1.0) == 1.0 and "KHR_materials_transmission" not in ext:
                # A smooth glTF metal: Schlick's Fresnel from F0 = the base colour, as Mitsuba's
                # `conductor` of the complex index closest to it (schlick_conductor).
                assert pbr.get("roughnessFactor", 1.0) == 0.0, "only smooth metals are mapped"
                eta_k = [schlick_conductor(f) for f in pbr.get("baseColorFactor", [1, 1, 1, 1])[:3]]
                shape["bsdf"] = {"type": "conductor", "eta": {"type": "rgb", "value": [e for e, _ in eta_k]},
                                 "k": {"type": "rgb", "value": [k for _, k in eta_k]}}
            elif "KHR_materials_transmission" in ext:
                ior = ext.get("KHR_materials_ior", {}).get("ior", 1.5)
                r = pbr.get("roughnessFactor", 1.0)
                if r > 0:
                    shape["bsdf"] = {"type": "roughdielectric", "distribution": "ggx", "alpha": r * r,
                                     "sample_visible": True, "int_ior": ior, "ext_ior": 1.0}
                else:
                    shape["bsdf"] = {"type": "dielectric", "int_ior": ior, "ext_ior": 1.0}
                if world_medium is not None:
                    shape["exterior"] = {"type": "ref", "id": "world_medium"}
                vol = ext.get("KHR_materials_volume", {})
                if "attenuationDistance" in vol:
                    sigma = [-math.log(c) / vol["attenuationDistance"] for c in vol["attenuationColor"]]
                    top = max(sigma)  # Mitsuba's RGB values are at most 1: scaled
                    shape["interior"] = {"type": "homogeneous", "albedo": 0.0, "scale": top,
                                         "sigma_t": {"type": "rgb", "value": [x / top for x in sigma]}}
                    has_medium = True
            else:
                c = pbr.get("baseColorFactor", [1, 1, 1, 1])[:3]
                refl = {"type": "rgb", "value": c}
                if "baseColorTexture" in pbr:
                    assert c == [1, 1, 1], "textured base colours here have factor 1"
                    refl = texture(doc, pbr["baseColorTexture"]["index"], tmp, "%s_%d_base" % (tag, k))
                # clppm's non-emissive surfaces reflect on both sides (docs/scenes.md, "Materials").
                inner = {"type": "diffuse", "reflectance": refl}
                if "normalTexture" in m:
                    assert m["normalTexture"].get("scale", 1.0) == 1.0, "normal maps here have scale 1"
                    # Mitsuba's normal map frame is (dp/du, n x dp/du, n); on these quads, whose v
                    # runs down the image, n x dp/du points up the image: glTF's +Y.
                    inner = {"type": "normalmap", "bsdf": inner, "use_shadowing_function": False,
                             "flip_invalid_normals": False,
                             "normalmap": texture(doc, m["normalTexture"]["index"], tmp, "%s_%d_normal" % (tag, k),
                                                  srgb=False)}
                # clppm's non-emissive surfaces reflect on both sides (docs/scenes.md, "Materials").
                shape["bsdf"] = {"type": "twosided", "bsdf": inner}
                if m.get("alphaMode") == "MASK":
                    shape["bsdf"] = {"type": "mask", "bsdf": shape["bsdf"],
                                     "opacity": texture(doc, pbr["baseColorTexture"]["index"], tmp,
                                                        "%s_%d_alpha" % (tag, k), alpha_cutoff=m.get("alphaCutoff", 0.5))}
            if "emissiveFactor" in m:
                s = ext.get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1.0)
                shape["emitter"] = {"type": "area",
                                    "radiance": {"type": "rgb", "value": [e * s for e in m["emissiveFactor"]]}}
            scene["%s_%d" % (tag, k)] = shape
    if has_medium:
        scene["integrator"] = {"type": "volpath", "max_depth": max_depth}
    return scene


def main():
    spp = int(sys.argv[1]) if len(sys.argv) > 1 else 65536
    names = sys.argv[2:] or SCENES
    mi.set_variant("scalar_rgb")
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            scene = mi.load_dict(mitsuba_scene(name, tmp))
            img = mi.render(scene, spp=spp)
            out = os.path.join(HERE, name + ".exr")
            mi.Bitmap(img).write(out)
            print(out, spp, "spp")


if __name__ == "__main__":
    main()

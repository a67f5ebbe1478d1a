"""The lists of options outside the option table agree with it (issue 61): the Renderer's settings,
--stats-json's options and the Blender add-on's integrators and defaults. An option that shapes the
image (role "image") or says when the render stops ("run") and is missing from any of them fails
here, as does an integrator the add-on does not offer or describes otherwise than the library."""
import ast
import json
import pathlib
import subprocess

import clppm
from conftest import SMALL

ADDON = pathlib.Path(__file__).resolve().parents[2] / "blender" / "clppm_blender" / "properties.py"


def shared_options():
    """The keyword names of every option whose role is image or run."""
    return {key for key, spec in clppm.options().items() if spec["role"] in ("image", "run")}


def test_every_role_is_known_and_the_image_options_include_the_integrator():
    roles = {spec["role"] for spec in clppm.options().values()}
    assert roles == {"image", "run", "local"}
    assert {"integrator", "seed", "alpha", "disc_coverage"} <= shared_options()
    assert "output" not in shared_options()


def test_settings_hold_every_image_and_run_option():
    with clppm.Renderer(**dict(SMALL, integrator="sppm", passes=2, disc_coverage="off")) as r:
        s = r.settings
    missing = shared_options() - set(s)
    assert not missing, "Renderer.settings lacks %s" % sorted(missing)
    assert s["integrator"] == "sppm" and s["disc_coverage"] == "off" and s["passes"] == 2 and s["seed"] == 3


def test_stats_json_holds_every_image_and_run_option(tmp_path, clppm_binary):
    stats = tmp_path / "s.json"
    subprocess.run([clppm_binary, "--width", "8", "--height", "8", "--passes", "1", "--quiet", "--no-png",
                    "--sampler", "independent", "-o", str(tmp_path / "a.exr"), "--stats-json", str(stats)],
                   check=True, capture_output=True)
    options = json.loads(stats.read_text())["options"]
    flags = {"--" + key.replace("_", "-") for key in shared_options()}
    assert flags == set(options), "--stats-json options differ: %s" % sorted(flags ^ set(options))
    assert options["--sampler"] == "independent"


def addon_assignments():
    """properties.py's module-level constants and the ClppmSceneSettings properties' keywords, read
    without Blender (ast)."""
    tree = ast.parse(ADDON.read_text())
    constants, props = {}, {}
    for node in tree.body:
        if isinstance(node, ast.Assign) and isinstance(node.targets[0], ast.Name):
            constants[node.targets[0].id] = ast.literal_eval(node.value)
        if isinstance(node, ast.ClassDef) and node.name == "ClppmSceneSettings":
            for item in node.body:
                if isinstance(item, ast.AnnAssign) and isinstance(item.annotation, ast.Call):
                    props[item.target.id] = {k.arg: ast.literal_eval(k.value) for k in item.annotation.keywords
                                             if k.arg in ("default", "min", "max", "items", "description")
                                             and not isinstance(k.value, ast.Name)}
    return constants, props


def test_the_blender_addon_offers_the_librarys_integrators():
    constants, props = addon_assignments()
    offered = constants["INTEGRATORS"]
    library = clppm.integrators()
    assert [i[0] for i in offered] == [i["name"] for i in library]
    for (name, _label, description), row in zip(offered, library):
        summary = row["summary"]
        assert description == summary[0].upper() + summary[1:], "%s: the add-on says %r, the library %r" % (
            name, description, summary)
    assert props["integrator"]["default"] == clppm.options()["integrator"]["default"]


def test_the_blender_addons_defaults_are_the_librarys():
    _, props = addon_assignments()
    options = clppm.options()
    for key in ("alpha", "seed"):
        assert str(props[key]["default"]) == options[key]["default"], key
    # Photons: 0 leaves the choice to the library (its default, and its own in media), which the
    # description names.
    assert props["photons"]["default"] == 0 and props["photons"]["min"] == 0
    assert props["photons"]["max"] == 2147483647
    assert "0: the library's default, %s," % options["photons"]["default"] in props["photons"]["description"]
    assert "10000 in participating media" in options["photons"]["help"], options["photons"]
    assert props["alpha"]["max"] == 1.0

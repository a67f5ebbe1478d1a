#!/usr/bin/env python3
"""Packages the Blender add-on (blender/clppm_blender) two ways, into OUT_DIR (default dist/):
  clppm_blender-VERSION.zip         a Blender 4.2+ extension: blender_manifest.toml at the zip's root
                                    (Preferences > Get Extensions > Install from Disk, or
                                    `blender --command extension install-file -r user_default FILE`)
  clppm_blender-VERSION-legacy.zip  a legacy add-on: the package folder in the zip
                                    (Preferences > Add-ons > Install from Disk, Blender before 4.2 too)
The version is the manifest's; bl_info must agree with it (checked here)."""
import ast
import os
import re
import sys
import zipfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PACKAGE = os.path.join(ROOT, "blender", "clppm_blender")


def manifest_version():
    text = open(os.path.join(PACKAGE, "blender_manifest.toml")).read()
    found = re.search(r'^version\s*=\s*"([^"]+)"', text, re.M)
    if not found:
        sys.exit("package_blender: blender/clppm_blender/blender_manifest.toml has no version")
    return found.group(1)


def bl_info_version():
    tree = ast.parse(open(os.path.join(PACKAGE, "__init__.py")).read())
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", "") == "bl_info" for t in node.targets):
            return ".".join(str(v) for v in ast.literal_eval(node.value)["version"])
    sys.exit("package_blender: blender/clppm_blender/__init__.py has no bl_info")


def files():
    for name in sorted(os.listdir(PACKAGE)):
        if name.endswith((".py", ".toml")):
            yield name


def write(path, prefix):
    tmp = path + ".tmp"
    with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
        for name in files():
            z.write(os.path.join(PACKAGE, name), prefix + name)
    os.replace(tmp, path)  # atomically: a half-written zip is never left under the final name
    print("package_blender: wrote", path)


def main():
    out = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "dist"))
    version = manifest_version()
    if bl_info_version() != version:
        sys.exit("package_blender: bl_info's version %s is not the manifest's %s" % (bl_info_version(), version))
    os.makedirs(out, exist_ok=True)
    write(os.path.join(out, "clppm_blender-%s.zip" % version), "")
    write(os.path.join(out, "clppm_blender-%s-legacy.zip" % version), "clppm_blender/")


if __name__ == "__main__":
    main()

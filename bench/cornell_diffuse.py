#!/usr/bin/env python3
"""Writes the Cornell box without its glass and mirror spheres (a diffuse room, the path tracer's
home ground) to the file named by argv[2], from scenes/cornell_box.gltf (argv[1]). Used by the
benchmark scripts; tests/sobol_test.cpp drops the same two nodes."""
import json
import sys

d = json.load(open(sys.argv[1]))
d["scenes"][0]["nodes"] = [n for n in d["scenes"][0]["nodes"]
                           if d["nodes"][n].get("name") not in ("glass_sphere", "mirror_sphere")]
json.dump(d, open(sys.argv[2], "w"))

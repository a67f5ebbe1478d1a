"""What the scripts that run clppm beside other renderers share (bench/peers_*.py): clppm timed
as those renderers are, `clppm compare --box 4` as JSON, and the table they print. Pure Python:
each peer's library loads in the script's own process, and some cannot share one (pyluxcore and
Mitsuba's Dr.Jit)."""
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def mitsuba_fastest_variant(mi):
    """Mitsuba's LLVM variant where Dr.Jit finds an LLVM it accepts, else the scalar one; returns its name."""
    try:
        mi.set_variant("llvm_ad_rgb")
    except Exception:  # no LLVM that Dr.Jit accepts
        mi.set_variant("scalar_rgb")
    return mi.variant()


def arguments():
    """[BUILD_DIR] [SECONDS] [SIZE] [REF_PASSES] from the command line, and REF_FACTOR from the
    environment: (clppm binary, seconds, size, ref_passes, ref_factor)."""
    build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build")
    seconds = float(sys.argv[2]) if len(sys.argv) > 2 else 15
    size = int(sys.argv[3]) if len(sys.argv) > 3 else 128
    ref_passes = int(sys.argv[4]) if len(sys.argv) > 4 else 40000
    return os.path.join(build, "clppm"), seconds, size, ref_passes, int(os.environ.get("REF_FACTOR", "20"))


def diffuse_box(binary, tmp, size, ref_passes, env=None):
    """The diffuse Cornell box (bench/cornell_diffuse.py) in tmp, clppm's path-tracing command line
    for it at size x size, and its reference: PEERS_REF when that names a file (a cached reference of
    the same settings), else the path tracer with independent numbers, seed 777, ref_passes passes.
    Returns (scene file, command, reference)."""
    scene_file = os.path.join(tmp, "cornell_diffuse.gltf")
    subprocess.run([sys.executable, os.path.join(HERE, "cornell_diffuse.py"),
                    os.path.join(ROOT, "scenes", "cornell_box.gltf"), scene_file], check=True)
    common = [binary, scene_file, "--integrator", "pt", "--width", str(size), "--height", str(size), "--quiet",
              "--no-png"]
    ref = os.environ.get("PEERS_REF", "")
    if not os.path.isfile(ref):
        ref = os.path.join(tmp, "ref.exr")
        subprocess.run(common + ["--sampler", "independent", "--seed", "777", "--passes", str(ref_passes), "-o", ref],
                       check=True, env=env)
    return scene_file, common, ref


def compare(binary, image, ref, env=None):
    """`clppm compare IMAGE REF --box 4` as a dict (mean_ratio, box_rel_mse, p90_rel_error, ...)."""
    out = subprocess.run([binary, "compare", image, ref, "--box", "4"], capture_output=True, text=True, check=True,
                         env=env)
    return json.loads(out.stdout)


def clppm_timed(command, stats, env=None):
    """Runs clppm (`command`, which writes --stats-json `stats`): (wall s of its passes alone, as the
    peers' renders are timed, CPU s of the whole process, passes)."""
    c0 = os.times()
    subprocess.run(command + ["--stats-json", stats], check=True, env=env)
    c1 = os.times()
    cpu = c1.children_user + c1.children_system - c0.children_user - c0.children_system
    st = json.load(open(stats))
    return st["render_seconds"], cpu, st["passes"]


def print_report(title, cross, rows):
    """The setup line `title`, how the two renderers' references agree (compare's dict `cross`),
    then print_table(rows)."""
    print(title)
    print("The two references against each other: mean ratio %.4f, box-4 relative MSE %.2e, p90 %.4f"
          % (cross["mean_ratio"], cross["box_rel_mse"], cross["p90_rel_error"]))
    print()
    print_table(rows)


def print_table(rows):
    """One row per (name, spp, wall s, CPU s, compare's dict). The error falls as 1/time: MSE x CPU
    time compares renderers at equal error (lower is better). MSE x spp is the error of one sample
    per pixel: how good each renderer's samples are, apart from how fast it draws them (spp / CPU s)."""
    print("| renderer | spp | render wall s | CPU s | spp / CPU s | mean ratio | box-4 relative MSE | p90 relative "
          "error | MSE x spp | MSE x CPU s |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, spp, wall, cpu, c in rows:
        print("| %s | %d | %.1f | %.1f | %.1f | %.4f | %.3e | %.4f | %.2e | %.2e |"
              % (name, spp, wall, cpu, spp / cpu, c["mean_ratio"], c["box_rel_mse"], c["p90_rel_error"],
                 c["box_rel_mse"] * spp, c["box_rel_mse"] * cpu))

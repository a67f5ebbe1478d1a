#!/usr/bin/env bash
# The Blender add-on in Blender's own window (Debian's blender under Xvfb): F12 renders in the
# render job's thread, the export is handed to the main thread, the image editor updates as the
# render converges, and Esc ends the job within a second with the last pass kept. Exits 77
# (ctest: skipped), saying so, without blender or xvfb-run (optional in scripts/install-deps.sh).
# Usage: check_blender_ui.sh WORK_DIR MODULE_DIR
set -euo pipefail
dir=$1 module=$2
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
for tool in blender xvfb-run; do
  if ! command -v $tool >/dev/null; then
    echo "check_blender_ui: skipped: no $tool (Debian's blender and xvfb, optional in scripts/install-deps.sh)"
    exit 77
  fi
done
mkdir -p "$dir"
log=$dir/blender_ui.jsonl
rm -f "$log"
# Debian's blender runs Debian's python3, for which the build made the module.
HOME=$dir timeout 300 xvfb-run -a -s "-screen 0 1280x1024x24" blender --factory-startup --python-exit-code 1 \
  --python "$root/tests/blender_ui/f12_in_the_window.py" -- "$log" "$root/blender" "$module" >"$dir/blender_ui.out" 2>&1 ||
  { echo "check_blender_ui: blender failed:"; tail -20 "$dir/blender_ui.out"; exit 1; }
python3 - "$log" <<'PY'
import json, sys
events = [json.loads(l) for l in open(sys.argv[1])]
kinds = [e["event"] for e in events]
print("check_blender_ui:", ", ".join(kinds[:3]), "...", ", ".join(kinds[-4:]))
def one(kind):
    found = [e for e in events if e["event"] == kind]
    assert found, "no %s in %s" % (kind, kinds)
    return found[0]
errors = [e["message"] for e in events if e["event"] == "error"]
assert not errors, errors
assert one("export")["render_thread_is_main"] is False, "F12 rendered on the main thread: nothing was checked"
shown = [e for e in events if e["event"] == "show" and e["mean"]]
assert len(shown) >= 3, "the image was shown %d times before Esc" % len(shown)
assert all(s["mean"] > 0 for s in shown) and shown[-1]["status"]["pass"] > shown[0]["status"]["pass"], shown
assert one("job_running_before_esc")["running"] is True
ended, esc, job = one("ended"), one("esc"), one("job_ended")
assert ended["interrupted"] is True and ended["error"] is None, ended
assert ended["at"] - esc["at"] < 3.0, "the engine stopped %.2f s after Esc" % (ended["at"] - esc["at"])
assert job["running"] is False and job["seconds"] < 5.0, job
print("check_blender_ui: F12 rendered in the job's thread, %d updates, passes %d to %d; Esc: the engine "
      "stopped in %.2f s, the job in %.2f s" % (len(shown), shown[0]["status"]["pass"], shown[-1]["status"]["pass"],
                                               ended["at"] - esc["at"], job["seconds"]))
PY

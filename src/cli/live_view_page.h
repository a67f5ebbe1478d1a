// The live view's page (cli/live_view.h): one HTML document with its script and style inline, so
// it works offline and behind any firewall. It polls /stats twice a second, reloads the image
// when a new one was published, and has an exposure slider, an error-map toggle (when the render
// estimates its error), and Save and Stop buttons.
#pragma once

namespace clppm {

inline const char* live_view_page() {
    return R"html(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>clppm</title>
<meta name="viewport" content="width=device-width, initial-scale=1">
<style>
body { background: #1b1b1b; color: #ddd; font: 14px system-ui, sans-serif; margin: 0; }
header { padding: 8px 12px; background: #262626; display: flex; flex-wrap: wrap; gap: 12px; align-items: center; }
#stats { font-family: ui-monospace, monospace; white-space: pre; }
main { padding: 12px; }
img { image-rendering: pixelated; max-width: 100%; background: #000; }
button { background: #3a3a3a; color: #eee; border: 1px solid #555; padding: 4px 10px; cursor: pointer; }
button:disabled { opacity: 0.4; cursor: default; }
#msg { color: #8c8; }
</style></head>
<body>
<header>
  <strong>clppm</strong>
  <label>exposure <input id="ev" type="range" min="-8" max="8" step="0.25" value="0"> <span id="evv">0</span> EV</label>
  <label id="maplabel" hidden><input id="map" type="checkbox"> error map</label>
  <button id="save">Save</button>
  <button id="stop">Stop</button>
  <span id="msg"></span>
</header>
<main>
  <div id="stats">connecting...</div>
  <img id="img" alt="the render">
</main>
<script>
"use strict";
const $ = (id) => document.getElementById(id);
let shown = -1, want = "";
function fmt(s) {
  if (!(s >= 0)) return "?";
  s = Math.round(s);
  if (s < 60) return s + "s";
  if (s < 3600) return Math.floor(s / 60) + "m" + String(s % 60).padStart(2, "0") + "s";
  return Math.floor(s / 3600) + "h" + String(Math.floor(s / 60) % 60).padStart(2, "0") + "m";
}
function src(v) {
  return "/image.png?v=" + v + "&ev=" + $("ev").value + ($("map").checked ? "&map=error" : "");
}
async function poll() {
  try {
    const r = await fetch("/stats", { cache: "no-store" });
    const s = await r.json();
    const p = s.progress || {};
    let t = s.state + "  pass " + (p.pass ?? 0) + (p.pass_limit ? "/" + p.pass_limit : "") +
      "  photons " + (p.photons ?? 0) + "  r " + (p.radius ?? 0).toPrecision(3) +
      "  " + (p.passes_per_second > 0 ? p.passes_per_second.toFixed(2) : "-") + " pass/s" +
      "  " + fmt(p.elapsed_s) + "  ETA " + fmt(p.eta_s);
    if (p.error >= 0) t += "  error " + p.error.toPrecision(3) + (p.target_error > 0 ? "/" + p.target_error : "");
    $("stats").textContent = t;
    $("maplabel").hidden = !s.has_error_map;
    const next = src(s.version);
    if (s.version > 0 && next !== want) { want = next; $("img").src = next; }
    const live = s.state === "rendering";
    $("save").disabled = !live; $("stop").disabled = !live;
  } catch (e) {
    $("stats").textContent = "the render has ended (or the server is unreachable)";
    $("save").disabled = true; $("stop").disabled = true;
  }
}
async function post(path, what) {
  const r = await fetch(path, { method: "POST" });
  $("msg").textContent = r.ok ? what : "failed: " + r.status;
}
$("ev").oninput = () => { $("evv").textContent = $("ev").value; want = ""; poll(); };
$("map").onchange = () => { want = ""; poll(); };
$("save").onclick = () => post("/save", "saving after this pass");
$("stop").onclick = () => post("/stop", "stopping after this pass");
poll();
setInterval(poll, 500);
</script>
</body></html>
)html";
}

} // namespace clppm

// The live view's page (cli/live_view.h): one HTML document with its script and style inline, so
// it works offline and behind any firewall. It polls /stats twice a second and fetches the image
// when a new one was published, and has an exposure slider, an error-map toggle (when the render
// estimates its error), a choice of transfer, and Save and Stop buttons.
//
// Transfer (?transport= or the menu): "f16" fetches the linear image as half floats
// (io/half_image.h) and applies exposure, tone curve and sRGB here, through a 65536-entry table
// from binary16 bits to 8-bit sRGB built for each exposure, so moving the slider needs no request;
// "png" fetches the PNG the server encodes at that exposure. Both decode into the same canvas,
// and the line under the buttons says what the last update cost. The default is f16, the faster
// on every size measured (bench/live_view_transport.sh, RESULTS.md). The error map is a PNG.
//
// For tests and the benchmark: ?check=1 draws a half-float frame, fetches the PNG of the same
// publication and writes how many 8-bit values differ and by how much; ?bench=N times N updates
// with each transfer and writes the medians. Both write JSON into the page (#check, #bench) and
// its title, which a headless browser's DevTools endpoint (/json/list) reports without a
// protocol client; real time, not a headless browser's virtual time, which skips network waits.
#pragma once

namespace clppm {

inline const char* live_view_page() {
    return R"html(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>clppm</title>
<meta name="viewport" content="width=device-width, initial-scale=1">
<style>
body { background: #1b1b1b; color: #ddd; font: 14px system-ui, sans-serif; margin: 0; }
header { padding: 8px 12px; background: #262626; display: flex; flex-wrap: wrap; gap: 12px; align-items: center; }
#stats, #cost { font-family: ui-monospace, monospace; white-space: pre; }
#cost { color: #999; }
main { padding: 12px; }
canvas { image-rendering: pixelated; max-width: 100%; background: #000; }
button, select { background: #3a3a3a; color: #eee; border: 1px solid #555; padding: 4px 10px; cursor: pointer; }
button:disabled { opacity: 0.4; cursor: default; }
#msg { color: #8c8; }
</style></head>
<body>
<header>
  <strong>clppm</strong>
  <label>exposure <input id="ev" type="range" min="-8" max="8" step="0.25" value="0"> <span id="evv">0</span> EV</label>
  <label id="maplabel" hidden><input id="map" type="checkbox"> error map</label>
  <label>transfer <select id="transport"><option value="f16">half floats</option><option value="png">PNG</option></select></label>
  <button id="save">Save</button>
  <button id="stop">Stop</button>
  <span id="msg"></span>
</header>
<main>
  <div id="stats">connecting...</div>
  <div id="cost"></div>
  <canvas id="img" width="1" height="1"></canvas>
  <pre id="check" hidden></pre><pre id="bench" hidden></pre>
</main>
<script>
"use strict";
const $ = (id) => document.getElementById(id);
const params = new URLSearchParams(location.search);
if (params.get("transport") === "png") $("transport").value = "png";
let tone = { curve: "clip", base_ev: 0 }, version = 0, drawn = "", busy = false;
let frame = null; // the last half-float image: {w, h, base_ev, halves, version}

function fmt(s) {
  if (!(s >= 0)) return "?";
  s = Math.round(s);
  if (s < 60) return s + "s";
  if (s < 3600) return Math.floor(s / 60) + "m" + String(s % 60).padStart(2, "0") + "s";
  return Math.floor(s / 3600) + "h" + String(Math.floor(s / 60) % 60).padStart(2, "0") + "m";
}

// The PNG's mapping (io/tone_map.cpp, io/image_io.cpp linear_to_srgb8), term for term: the curve
// in double, rounded to float, then the sRGB OETF rounded to the nearest 8-bit value.
function curve(name, x) {
  if (!(x > 0)) return 0;
  if (name === "aces") {
    if (x === Infinity) return 1;
    return Math.min(1, x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14));
  }
  if (name === "reinhard") return x === Infinity ? 1 : x / (1 + x);
  return Math.min(x, 1);
}
function srgb8(linear) {
  const v = linear > 0 ? Math.min(linear, 1) : 0;
  const e = v <= 0.0031308 ? 12.92 * v : 1.055 * Math.pow(v, 1 / 2.4) - 0.055;
  return Math.round(e * 255);
}
function halfToFloat(h) {
  const s = h & 0x8000 ? -1 : 1, e = (h >> 10) & 31, m = h & 1023;
  if (e === 0) return s * m * Math.pow(2, -24);
  if (e === 31) return m ? NaN : s * Infinity;
  return s * (1 + m / 1024) * Math.pow(2, e - 15);
}
// 8-bit sRGB for every binary16 pattern at `ev` stops above the stored values; 256 marks NaN.
let lutKey = "", lut = null;
function table(ev) {
  const key = tone.curve + ":" + ev;
  if (key === lutKey) return lut;
  const scale = Math.pow(2, ev), t = new Uint16Array(65536);
  for (let h = 0; h < 65536; ++h) {
    const f = halfToFloat(h);
    t[h] = Number.isNaN(f) ? 256 : srgb8(Math.fround(curve(tone.curve, f * scale)));
  }
  lutKey = key; lut = t;
  return t;
}
function drawHalves(f, ev) {
  const t = table(ev), n = f.w * f.h, out = new ImageData(f.w, f.h), d = out.data, src = f.halves;
  for (let i = 0; i < n; ++i) {
    const r = t[src[3 * i]], g = t[src[3 * i + 1]], b = t[src[3 * i + 2]];
    const nan = r === 256 || g === 256 || b === 256; // magenta, as the PNG
    d[4 * i] = nan ? 255 : r; d[4 * i + 1] = nan ? 0 : g; d[4 * i + 2] = nan ? 255 : b; d[4 * i + 3] = 255;
  }
  const c = $("img");
  if (c.width !== f.w || c.height !== f.h) { c.width = f.w; c.height = f.h; }
  c.getContext("2d").putImageData(out, 0, 0);
  return out;
}
function timing(r) {
  const m = /dur=([0-9.]+)/.exec(r.headers.get("Server-Timing") || "");
  return m ? parseFloat(m[1]) : NaN;
}
async function fetchHalves() {
  const r = await fetch("/image.f16", { cache: "no-store" });
  if (!r.ok) throw new Error("image.f16: " + r.status);
  const buf = await r.arrayBuffer(), dv = new DataView(buf);
  if (dv.getUint32(0, true) !== 0x31484c43) throw new Error("image.f16: not CLH1");
  const w = dv.getUint32(4, true), h = dv.getUint32(8, true);
  return { w, h, base_ev: dv.getFloat32(12, true), halves: new Uint16Array(buf, 16, w * h * 3),
           version: +r.headers.get("X-Clppm-Version"), bytes: buf.byteLength, encode_ms: timing(r) };
}
async function fetchPng(query) {
  const r = await fetch("/image.png?" + query, { cache: "no-store" });
  if (!r.ok) throw new Error("image.png: " + r.status);
  const blob = await r.blob();
  const bmp = await createImageBitmap(blob, { colorSpaceConversion: "none", premultiplyAlpha: "none" });
  const c = $("img");
  if (c.width !== bmp.width || c.height !== bmp.height) { c.width = bmp.width; c.height = bmp.height; }
  const ctx = c.getContext("2d");
  ctx.drawImage(bmp, 0, 0);
  return { version: +r.headers.get("X-Clppm-Version"), bytes: blob.size, encode_ms: timing(r),
           pixels: ctx.getImageData(0, 0, bmp.width, bmp.height) };
}
// One update of the canvas: what to show, fetched only when the publication or (for the PNG)
// the exposure changed. Returns its cost.
async function update(fresh) {
  const ev = +$("ev").value, t0 = performance.now();
  let how, bytes = 0, encode = NaN;
  if ($("map").checked) {
    const p = await fetchPng("map=error"); how = "error map PNG"; bytes = p.bytes; encode = p.encode_ms;
  } else if ($("transport").value === "f16") {
    if (fresh || !frame || frame.version !== version) { frame = await fetchHalves(); bytes = frame.bytes; encode = frame.encode_ms; }
    drawHalves(frame, ev); how = "half floats";
  } else {
    const p = await fetchPng("ev=" + ev); how = "PNG"; bytes = p.bytes; encode = p.encode_ms;
  }
  const ms = performance.now() - t0;
  $("cost").textContent = "last update " + ms.toFixed(1) + " ms (" + how +
    (bytes ? ", " + (bytes / 1024).toFixed(0) + " KiB, server encode " + encode.toFixed(1) + " ms" : ", redrawn here") + ")";
  return { ms, bytes, encode_ms: encode };
}
async function refresh() {
  const key = version + "|" + $("ev").value + "|" + $("map").checked + "|" + $("transport").value;
  if (version === 0 || busy || key === drawn) return;
  busy = true;
  try { await update(false); drawn = key; }
  catch (e) { $("cost").textContent = String(e); }
  busy = false;
}
async function poll() {
  try {
    const r = await fetch("/stats", { cache: "no-store" });
    const s = await r.json();
    const p = s.progress || {};
    if (s.tone) tone = s.tone;
    let t = s.state + "  pass " + (p.pass ?? 0) + (p.pass_limit ? "/" + p.pass_limit : "") +
      "  photons " + (p.photons ?? 0) + "  r " + (p.radius ?? 0).toPrecision(3) +
      "  " + (p.passes_per_second > 0 ? p.passes_per_second.toFixed(2) : "-") + " pass/s" +
      "  " + fmt(p.elapsed_s) + "  ETA " + fmt(p.eta_s);
    if (p.error >= 0) t += "  error " + p.error.toPrecision(3) + (p.target_error > 0 ? "/" + p.target_error : "");
    $("stats").textContent = t;
    $("maplabel").hidden = !s.has_error_map;
    version = s.version;
    const live = s.state === "rendering";
    $("save").disabled = !live; $("stop").disabled = !live;
    refresh();
  } catch (e) {
    $("stats").textContent = "the render has ended (or the server is unreachable)";
    $("save").disabled = true; $("stop").disabled = true;
  }
}
async function post(path, what) {
  const r = await fetch(path, { method: "POST" });
  $("msg").textContent = r.ok ? what : "failed: " + r.status;
}
async function waitForImage() {
  for (;;) {
    const s = await (await fetch("/stats", { cache: "no-store" })).json();
    if (s.tone) tone = s.tone;
    if (s.version > 0) return;
    await new Promise((ok) => setTimeout(ok, 100));
  }
}
// ?check=1: the page's tone mapping of the half floats against the server's PNG, same publication.
async function check() {
  await waitForImage();
  for (let attempt = 0; attempt < 50; ++attempt) {
    const f = await fetchHalves(), mine = drawHalves(f, 0).data;
    const p = await fetchPng("ev=0");
    if (p.version !== f.version) continue; // a new publication in between: again
    let differ = 0, max = 0;
    for (let i = 0; i < mine.length; ++i) {
      if ((i & 3) === 3) continue;
      const d = Math.abs(mine[i] - p.pixels.data[i]);
      if (d) { ++differ; max = Math.max(max, d); }
    }
    return { version: f.version, values: mine.length / 4 * 3, differ, max_diff: max, curve: tone.curve };
  }
  return { error: "no two fetches of the same publication in 50 attempts" };
}
// ?bench=N: N updates with each transfer, at a fixed exposure; medians of the page's time (fetch,
// decode, draw), the server's encode time, and the bytes.
async function bench(n) {
  await waitForImage();
  const med = (a) => a.slice().sort((x, y) => x - y)[a.length >> 1], out = {};
  for (const t of ["png", "f16"]) {
    $("transport").value = t;
    const runs = [];
    for (let i = 0; i < n + 1; ++i) runs.push(await update(true));
    runs.shift(); // the first builds the table and warms the code
    out[t] = { ms: med(runs.map((r) => r.ms)), encode_ms: med(runs.map((r) => r.encode_ms)),
               bytes: med(runs.map((r) => r.bytes)) };
  }
  out.width = $("img").width; out.height = $("img").height;
  return out;
}
async function report(id, job) {
  let result;
  try { result = await job; } catch (e) { result = { error: String(e) }; }
  $(id).textContent = JSON.stringify(result); $(id).hidden = false;
  document.title = JSON.stringify(result); // read through the DevTools HTTP endpoint /json/list
}

$("ev").oninput = () => { $("evv").textContent = $("ev").value; refresh(); };
$("map").onchange = () => refresh();
$("transport").onchange = () => refresh();
$("save").onclick = () => post("/save", "saving after this pass");
$("stop").onclick = () => post("/stop", "stopping after this pass");
if (params.has("check")) report("check", check());
else if (params.has("bench")) report("bench", bench(Math.max(1, +params.get("bench") || 10)));
else { poll(); setInterval(poll, 500); }
</script>
</body></html>
)html";
}

} // namespace clppm

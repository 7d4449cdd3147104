#include "app/preview_page.hpp"

namespace wp {

// kPreviewImageLeft and kPreviewImageTop are the #view rule's left and top,
// and the margins that layout() leaves.
const char* const kPreviewPage = R"html(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>wavepath preview</title>
<style>
  html, body { margin: 0; background: #202020; color: #e0e0e0; font: 14px sans-serif; }
  #bar { position: fixed; left: 0; top: 0; right: 0; height: 40px; display: flex;
         align-items: center; gap: 16px; padding: 0 8px; background: #303030; }
  #stats { flex: 1; white-space: nowrap; overflow: hidden; font-variant-numeric: tabular-nums; }
  #stop { font: inherit; padding: 4px 12px; }
  #view { position: absolute; left: 8px; top: 48px; image-rendering: pixelated; }
</style>
</head>
<body>
<div id="bar"><b>wavepath</b><span id="stats">connecting...</span>
  <button id="stop" title="End the render as Ctrl-C does: the outputs are written">Stop</button></div>
<img id="view" alt="">
<script>
"use strict";
const view = document.getElementById("view");
const stats = document.getElementById("stats");
const stop = document.getElementById("stop");
let shownSpp = -1, loading = false;

// The largest whole scale that fits the window (crisp pixels), or a
// fractional one below 1 for an image larger than the window.
function layout() {
  const w = view.naturalWidth, h = view.naturalHeight;
  if (!w || !h) return;
  const fit = Math.min((innerWidth - 16) / w, (innerHeight - 56) / h);
  const scale = fit >= 1 ? Math.floor(fit) : fit;
  view.style.width = (w * scale) + "px";
  view.style.height = (h * scale) + "px";
}

function duration(s) {
  if (s < 60) return s.toFixed(1) + " s";
  if (s < 3600) return Math.floor(s / 60) + " min " + Math.floor(s % 60) + " s";
  return Math.floor(s / 3600) + " h " + Math.floor(s / 60 % 60) + " min";
}

function show(status) {
  const parts = [status.spp + (status.spp_goal ? "/" + status.spp_goal : "") + " spp",
                 status.samples_per_second.toPrecision(3) + " samples/s",
                 duration(status.elapsed_seconds) + " elapsed"];
  if (status.seconds_left !== null) parts.push(duration(status.seconds_left) + " left");
  if (status.rel_mse !== null) parts.push("relMSE " + status.rel_mse.toPrecision(3));
  if (status.state !== "rendering") parts.push(status.state);
  stats.textContent = parts.join(" \u00b7 ");
  stop.disabled = status.state !== "rendering";
  if (status.spp !== shownSpp && status.spp > 0 && !loading) {
    // Load off-screen and swap, so the page never shows a half-loaded image.
    const next = new Image();
    loading = true;
    next.onload = () => { view.src = next.src; shownSpp = status.spp; loading = false; };
    next.onerror = () => { loading = false; };
    next.src = "image.png?spp=" + status.spp;
  }
}

async function poll() {
  try {
    const response = await fetch("status.json", { cache: "no-store" });
    show(await response.json());
  } catch (e) {
    stats.textContent = "the render has ended (" + (shownSpp > 0 ? shownSpp + " spp shown" : "no image") + ")";
    stop.disabled = true;
  }
}

view.addEventListener("load", layout);
addEventListener("resize", layout);
stop.addEventListener("click", async () => {
  stop.disabled = true;
  try { await fetch("stop", { method: "POST" }); } catch (e) {}
  poll();
});
poll();
setInterval(poll, 1000);
</script>
</body>
</html>
)html";

} // namespace wp

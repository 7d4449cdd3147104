#!/usr/bin/env python3
"""Renders the gallery of third-party scenes (docs/gallery.md): each scene
of tests/data/third-party/mitsuba-data, unchanged, by wavepath and by
Mitsuba 3 at the same size and sample count, and writes for each a small
PNG of wavepath's image, of Mitsuba's and of their difference, and prints
the gallery's table (times, sample counts, image means).

    python3 tools/render-gallery.py [--wavepath build/wavepath] [--spp 256]
                                    [--out-dir docs/images/gallery]

Both renderers read the file as it is, with the same -D values: the size
(res, or width and height); each applies the file's max_depth
(docs/mitsuba-import.md, "max_depth"). Mitsuba renders with
`llvm_ad_rgb` through bench/peers_mitsuba.py (2 threads), wavepath with
`wavepath render` (PoCL, 2 threads); each time is the renderer's own
(wavepath's --profile-json wall time, Mitsuba's render call), loading
excluded. The PNGs share one exposure per scene (linear, scaled so that the
Mitsuba image's mean maps to 0.18, gamma 1/2.2); the difference is
|wavepath - Mitsuba| per channel at 4 times that exposure, so that noise
shows as grain and a bias as a shape. Needs mitsuba, numpy and libLLVM
(tools/install-deps.sh --bench).
"""
import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPOSITORY / "bench"))
import peers_image  # noqa: E402
import peers_renderers  # noqa: E402

DATA = REPOSITORY / "tests/data/third-party/mitsuba-data/scenes"
# name, scene file, -D values (the size)
SCENES = [
    ("cbox", DATA / "cbox/cbox.xml", ["res=128"]),
    ("cbox-rgb", DATA / "cbox/cbox-rgb.xml", ["res=128"]),
    ("matpreview", DATA / "matpreview/matpreview.xml", ["width=171", "height=128"]),
]


def run(command, env=None):
    result = subprocess.run([str(c) for c in command], capture_output=True, text=True, env=env)
    if result.returncode != 0:
        lines = (result.stderr.strip() or result.stdout.strip() or "no output").splitlines()
        sys.exit(f"render-gallery: error: {Path(str(command[0])).name} failed: {lines[-1]}")
    return result.stdout


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--wavepath", default=str(REPOSITORY / "build" / "wavepath"))
    parser.add_argument("--spp", type=int, default=256)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--out-dir", default=str(REPOSITORY / "docs" / "images" / "gallery"))
    args = parser.parse_args()
    import numpy as np
    out = Path(args.out_dir)
    out.mkdir(parents=True, exist_ok=True)
    scratch = Path(os.environ.get("TMPDIR", "/tmp")) / "wavepath-gallery"
    scratch.mkdir(exist_ok=True)
    env = dict(os.environ, POCL_MAX_PTHREAD_COUNT=str(args.threads))
    library = os.environ.get("DRJIT_LIBLLVM_PATH") or next(
        (c for c in peers_renderers.LLVM_CANDIDATES if Path(c).exists()), None)
    if library:
        env["DRJIT_LIBLLVM_PATH"] = library
    rows = []
    for name, scene, defines in SCENES:
        flags = [f"--define={d}" for d in defines]
        wp_exr, mi_exr, profile = scratch / f"{name}-wavepath.exr", scratch / f"{name}-mitsuba.exr", \
            scratch / f"{name}.profile.json"
        run([args.wavepath, "render", scene, "--spp", args.spp, "--seed", 1, "-q", "--out", wp_exr,
             "--profile-json", profile] + flags, env)
        wp_seconds = json.loads(profile.read_text())["wall_seconds"]
        result = run([sys.executable, REPOSITORY / "bench/peers_mitsuba.py", scene, "--spp", args.spp,
                      "--seed", 1, "--threads", args.threads, "--out", mi_exr] + flags, env)
        mi_seconds = json.loads(result.strip().splitlines()[-1])["render_seconds"]
        ours, theirs = peers_image.read(wp_exr), peers_image.read(mi_exr)
        scale = 0.18 / max(1e-6, float(theirs.mean()))
        peers_image.write_png(ours, out / f"{name}-wavepath.png", scale)
        peers_image.write_png(theirs, out / f"{name}-mitsuba.png", scale)
        peers_image.write_png(np.abs(ours - theirs), out / f"{name}-difference.png", 4 * scale)
        rows.append((name, scene.relative_to(REPOSITORY), defines, ours.shape, wp_seconds, mi_seconds,
                     ours.reshape(-1, 3).mean(axis=0), theirs.reshape(-1, 3).mean(axis=0)))
        print(f"render-gallery: {name}: wavepath {wp_seconds:.2f} s, Mitsuba {mi_seconds:.2f} s",
              flush=True)
    load = " ".join(Path("/proc/loadavg").read_text().split()[:3])
    print(f"\n<!-- {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {args.spp} spp, "
          f"load {load} -->")
    print("| scene | size, spp | wavepath | Mitsuba 3 | time wavepath / Mitsuba | image mean wavepath | Mitsuba |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for name, scene, defines, shape, wp_s, mi_s, wp_mean, mi_mean in rows:
        print(f"| `{scene}` (-D {' -D '.join(defines)}) | {shape[1]}x{shape[0]}, {args.spp} | "
              f"![wavepath](images/gallery/{name}-wavepath.png) | ![Mitsuba](images/gallery/{name}-mitsuba.png) "
              f"| {wp_s:.2f} s / {mi_s:.2f} s | {peers_image.triple(wp_mean)} | {peers_image.triple(mi_mean)} |")
    print("\nDifferences (|wavepath - Mitsuba|, 4x the exposure): " + " ".join(
        f"![{name}](images/gallery/{name}-difference.png)" for name, *_ in rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())

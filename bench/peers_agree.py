#!/usr/bin/env python3
"""Does wavepath render a scene as Mitsuba 3 does? (issue #32)

    python3 bench/peers_agree.py SCENE.xml|SCENE.json [--spp 64] [--seeds 8]
                                 [--reference-spp 1024] [--sigma 5] [--out-dir DIR]
                                 [-D NAME=VALUE ...]
    python3 bench/peers.py agree SCENE ...        (the same)

Renders the scene K times (seeds 1..K) in Mitsuba 3 (`llvm_ad_rgb`, as
bench/peers_mitsuba.py runs it) and in wavepath, at the same sample count,
and once more in Mitsuba at --reference-spp. A Mitsuba XML file goes to both
unchanged; a wavepath JSON scene goes to Mitsuba through `wavepath
export-mitsuba`. Prints, and writes to DIR/agree.md and agree.json:

- per-channel image means of each renderer, each with its standard error
  from the K independent renders (sd / sqrt(K)), and their difference in
  combined standard errors (z); the same for a B x B grid of blocks, so that
  two pictures with equal means but different content tell apart;
- relMSE (as `wavepath compare` defines it) of each renderer's mean image
  against the long Mitsuba render, and their ratio (the long render's own
  noise is in both);
- render times (inside each renderer, as bench/peers.py measures them);
- a verdict: agree when every |z| is at most --sigma.

Writes DIR/agree-side-by-side.png (wavepath, Mitsuba, reference) and
DIR/agree-difference.png (`wavepath compare --diff` of wavepath's mean
image against Mitsuba's). Exit status 0 when they agree, 1 when not, 2 on a
failed render or missing tool, each with one line. A benchmark tool, never a
test: tests use committed references instead (tools/mitsuba-references.sh).
Needs mitsuba and numpy (pip) and libLLVM 19 (tools/install-deps.sh --bench).
"""
import argparse
import json
import math
import os
import shlex
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import peers_image  # noqa: E402
import peers_renderers  # noqa: E402

REPOSITORY = HERE.parent


def fail(message, status=2):
    print(f"peers agree: error: {message}", file=sys.stderr)
    sys.exit(status)


def mean_and_error(values):
    """The mean of K independent estimates (an array K x ...) and its standard
    error sd / sqrt(K), sd with K - 1 in the denominator."""
    import numpy as np
    values = np.asarray(values, dtype=np.float64)
    k = values.shape[0]
    mean = values.mean(axis=0)
    error = values.std(axis=0, ddof=1) / math.sqrt(k) if k > 1 else np.full_like(mean, math.inf)
    return mean, error


def write_exr(image, path):
    """A float RGB image as an EXR, through Mitsuba's Bitmap (as peers_image reads them)."""
    import mitsuba as mi
    import numpy as np
    if mi.variant() is None:
        mi.set_variant("scalar_rgb")
    mi.Bitmap(np.ascontiguousarray(image, dtype=np.float32)).write(str(path))


def mitsuba_scene(args, workdir):
    """The scene as Mitsuba reads it: an XML file as given, a JSON one exported."""
    scene = Path(args.scene)
    if scene.suffix.lower() == ".xml":
        return scene
    xml = workdir / (scene.stem + ".xml")
    peers_renderers.run([args.wavepath, "export-mitsuba", scene, xml], what="wavepath export-mitsuba")
    return xml


def render_mitsuba(args, env, xml, spp, seed, out):
    command = [sys.executable, HERE / "peers_mitsuba.py", xml, "--spp", spp, "--seed", seed,
               "--threads", args.threads, "--variant", args.variant, "--out", out]
    command += [f"--define={d}" for d in args.define]
    result = json.loads(peers_renderers.run(command, env, "Mitsuba render").strip().splitlines()[-1])
    return result["render_seconds"]


def render_wavepath(args, spp, seed, out):
    profile = Path(out).with_suffix(".profile.json")
    command = [args.wavepath, "render", args.scene, "--spp", spp, "--seed", seed, "-q", "--out", out,
               "--profile-json", profile] + shlex.split(args.wp_options)
    command += [f"--define={d}" for d in args.define]
    env = dict(os.environ, POCL_MAX_PTHREAD_COUNT=str(args.threads))
    peers_renderers.run(command, env, "wavepath render")
    return json.loads(profile.read_text())["wall_seconds"]


def compare(label, wavepath_values, mitsuba_values):
    """Means, standard errors and z per channel (the last axis) of one region."""
    import numpy as np
    w_mean, w_error = mean_and_error(wavepath_values)
    m_mean, m_error = mean_and_error(mitsuba_values)
    combined = np.sqrt(w_error ** 2 + m_error ** 2)
    z = np.where(combined > 0, (w_mean - m_mean) / np.where(combined > 0, combined, 1), 0.0)
    return {"region": label, "wavepath": w_mean.tolist(), "wavepath_error": w_error.tolist(),
            "mitsuba": m_mean.tolist(), "mitsuba_error": m_error.tolist(), "z": z.tolist()}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog=__doc__.split("\n\n", 1)[1])
    parser.add_argument("scene", help="a Mitsuba 3 XML scene or a wavepath JSON scene")
    parser.add_argument("--wavepath", default=str(REPOSITORY / "build" / "wavepath"))
    parser.add_argument("--spp", type=int, default=64, help="samples per pixel of each render (default: 64)")
    # Each standard error comes from the spread of K renders, itself uncertain
    # with K - 1 degrees of freedom: with 4 renders a |z| over 5 comes by chance
    # about once in 65 regions (Student's t, 3 degrees of freedom), with 8 once
    # in 640 (7).
    parser.add_argument("--seeds", type=int, default=8, help="independent renders per renderer (default: 8)")
    parser.add_argument("--reference-spp", type=int, default=1024,
                        help="samples per pixel of the long Mitsuba render (default: 1024)")
    parser.add_argument("--blocks", type=int, default=4, help="blocks per side of the grid (default: 4)")
    parser.add_argument("--sigma", type=float, default=5.0,
                        help="the largest |z| that still agrees (default: 5)")
    parser.add_argument("--wp-options", default="",
                        help="further options of every wavepath render, written with '=': "
                        "--wp-options='--roulette-depth 5'")
    parser.add_argument("-D", "--define", action="append", default=[], metavar="NAME=VALUE",
                        help="set the XML scene's $NAME in both renderers, as Mitsuba's -D "
                        "(repeatable): -D res=128 -D max_depth=3")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--variant", default="llvm_ad_rgb")
    parser.add_argument("--llvm", default=None, help="libLLVM for Mitsuba's llvm variant")
    parser.add_argument("--out-dir", default=str(REPOSITORY / "build" / "peers-out"),
                        help="where results go (default: build/peers-out, which git ignores)")
    args = parser.parse_args()
    if any("=" not in d or d.startswith("=") for d in args.define):
        fail("-D takes NAME=VALUE")
    if args.seeds < 2:
        fail("--seeds must be at least 2: the standard errors come from the spread of the renders")
    if args.spp < 1 or args.reference_spp < 1 or args.blocks < 1 or args.sigma <= 0:
        fail("--spp, --reference-spp and --blocks must be at least 1, --sigma positive")
    if not Path(args.wavepath).is_file():
        fail(f"wavepath binary '{args.wavepath}' does not exist (build it, or give --wavepath)")
    if not Path(args.scene).is_file():
        fail(f"scene '{args.scene}' does not exist")
    out = Path(args.out_dir)
    out.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ)
    if args.variant.startswith("llvm"):
        library = args.llvm or os.environ.get("DRJIT_LIBLLVM_PATH") or next(
            (c for c in peers_renderers.LLVM_CANDIDATES if Path(c).exists()), None)
        if not library:
            fail("no libLLVM for Mitsuba's llvm variant: apt-get install libllvm19 or give --llvm")
        env["DRJIT_LIBLLVM_PATH"] = library

    import numpy as np
    with tempfile.TemporaryDirectory(prefix="wavepath-agree-") as scratch:
        workdir = Path(scratch)
        try:
            xml = mitsuba_scene(args, workdir)
            render_mitsuba(args, env, xml, 1, 0, workdir / "warm.exr")  # fills Dr.Jit's kernel cache
            images = {"wavepath": [], "mitsuba": []}
            seconds = {"wavepath": [], "mitsuba": []}
            for seed in range(1, args.seeds + 1):  # alternating, so that drifting load hits both
                path = workdir / f"wavepath-{seed}.exr"
                seconds["wavepath"].append(render_wavepath(args, args.spp, seed, path))
                images["wavepath"].append(peers_image.read(path))
                path = workdir / f"mitsuba-{seed}.exr"
                seconds["mitsuba"].append(render_mitsuba(args, env, xml, args.spp, seed, path))
                images["mitsuba"].append(peers_image.read(path))
                print(f"peers agree: seed {seed}: wavepath {seconds['wavepath'][-1]:.2f} s, "
                      f"Mitsuba {seconds['mitsuba'][-1]:.2f} s", flush=True)
            reference_path = workdir / "reference.exr"
            reference_seconds = render_mitsuba(args, env, xml, args.reference_spp, 1000 + args.seeds,
                                               reference_path)
            reference = peers_image.read(reference_path)
        except peers_renderers.RendererError as error:
            fail(str(error))
        if images["wavepath"][0].shape != images["mitsuba"][0].shape:
            fail(f"wavepath renders {images['wavepath'][0].shape[1]}x{images['wavepath'][0].shape[0]}, "
                 f"Mitsuba {images['mitsuba'][0].shape[1]}x{images['mitsuba'][0].shape[0]}: "
                 "not the same film")

        stack = {name: np.stack(images[name]) for name in images}  # K x rows x columns x 3
        regions = [compare("image", stack["wavepath"].reshape(args.seeds, -1, 3).mean(axis=1),
                           stack["mitsuba"].reshape(args.seeds, -1, 3).mean(axis=1))]
        block_values = {name: np.stack([peers_image.block_means(i, args.blocks) for i in images[name]])
                        for name in images}
        for row in range(args.blocks):
            for column in range(args.blocks):
                regions.append(compare(f"block {row},{column}", block_values["wavepath"][:, row, column],
                                       block_values["mitsuba"][:, row, column]))
        mean_images = {name: stack[name].mean(axis=0) for name in stack}
        rel_mse = {name: peers_image.errors(mean_images[name], reference)[1] for name in mean_images}
        worst = max(regions[1:], key=lambda r: max(abs(z) for z in r["z"]))
        worst_z = max(abs(z) for z in worst["z"])
        image_z = max(abs(z) for z in regions[0]["z"])
        agree = max(image_z, worst_z) <= args.sigma

        peers_image.write_row([mean_images["wavepath"], mean_images["mitsuba"], reference],
                              out / "agree-side-by-side.png", scale=1.0 / max(1e-6, float(reference.mean()) * 4))
        mitsuba_mean_path = workdir / "mitsuba-mean.exr"
        wavepath_mean_path = workdir / "wavepath-mean.exr"
        write_exr(mean_images["mitsuba"], mitsuba_mean_path)
        write_exr(mean_images["wavepath"], wavepath_mean_path)
        compared = subprocess.run([args.wavepath, "compare", str(wavepath_mean_path), str(mitsuba_mean_path),
                                   "--diff", str(out / "agree-difference.png")],
                                  capture_output=True, text=True)
        if compared.returncode != 0:
            fail(f"wavepath compare failed: {(compared.stderr.strip() or 'no output').splitlines()[-1]}")

    def channels(values, errors=None):
        if errors is None:
            return " ".join(f"{v:.4f}" for v in values)
        return " ".join(f"{v:.4f}±{e:.4f}" for v, e in zip(values, errors))

    load = " ".join(Path("/proc/loadavg").read_text().split()[:3])
    header = (f"{Path(args.scene).name}: {args.seeds} renders of {args.spp} spp each, Mitsuba {args.variant} "
              f"reference at {args.reference_spp} spp; {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
              f"load {load}")
    md = [f"<!-- {header} -->", "",
          f"`python3 bench/peers_agree.py {args.scene} --spp {args.spp} --seeds {args.seeds} "
          f"--reference-spp {args.reference_spp}"
          + (f" --wp-options='{args.wp_options}'" if args.wp_options else "")
          + "".join(f" -D {d}" for d in args.define) + "`", "",
          "| region | wavepath (mean ± standard error, R G B) | Mitsuba 3 | z (R G B) |",
          "| --- | --- | --- | --- |"]
    for r in [regions[0], worst]:
        label = r["region"] + (" (largest |z| of the blocks)" if r is worst else "")
        md.append(f"| {label} | {channels(r['wavepath'], r['wavepath_error'])} | "
                  f"{channels(r['mitsuba'], r['mitsuba_error'])} | {channels(r['z'])} |")
    md += ["",
           f"relMSE of the mean of the {args.seeds} renders against the reference: wavepath "
           f"{rel_mse['wavepath']:.4g}, Mitsuba {rel_mse['mitsuba']:.4g} (ratio {rel_mse['wavepath'] / rel_mse['mitsuba']:.2f}); "
           f"render time per {args.spp}-spp render: wavepath {np.mean(seconds['wavepath']):.2f} s, "
           f"Mitsuba {np.mean(seconds['mitsuba']):.2f} s; the reference took {reference_seconds:.1f} s.",
           "",
           f"**{'Agree' if agree else 'DISAGREE'}**: largest |z| {max(image_z, worst_z):.2f} "
           f"(image {image_z:.2f}, blocks {worst_z:.2f}) against --sigma {args.sigma}."]
    (out / "agree.md").write_text("\n".join(md) + "\n")
    (out / "agree.json").write_text(json.dumps(
        {"header": header, "scene": args.scene, "spp": args.spp, "seeds": args.seeds,
         "reference_spp": args.reference_spp, "regions": regions, "rel_mse": rel_mse,
         "seconds": seconds, "reference_seconds": reference_seconds, "agree": agree,
         "largest_z": max(image_z, worst_z)}, indent=1) + "\n")
    print("\n".join(md))
    print(f"peers agree: wrote {out}/agree.md, agree.json, agree-side-by-side.png, agree-difference.png")
    return 0 if agree else 1


if __name__ == "__main__":
    sys.exit(main())

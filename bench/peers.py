#!/usr/bin/env python3
"""wavepath side by side with its peers on the hexroom (issues #11 and #12).

    python3 bench/peers.py throughput [--sizes 256,800] [--spp 64] [--rounds 3]
                                      [--baseline COMMIT | --baseline-binary PATH]
                                      [--wp-variant="--mirror-nee off"]
    python3 bench/peers.py error --reference REF.exr [--spp 16,64,256,1024] [--rounds 2]
                                 [--modes two-threads,one-core] [--wp-variant="--sampler sobol"]

throughput: whole-render time and samples/s of wavepath (its default and each
--wp-variant), Mitsuba 3 llvm_ad_rgb and (with --baseline) an earlier wavepath
build, at each size, 2 threads each;
then wavepath's intersect and shadow stages against Embree 1-ray and 16-ray
on the same 4x10^6 incoherent rays of the scene's free space (and its camera,
bounce and light rays), hits checked ray by ray, by build/bench/
wavepath_bench_bvh --scene (built with -DWAVEPATH_BUILD_BENCH=ON; skipped,
saying so, when it is not there).
error: MSE, relMSE, time, efficiency 1/(MSE t) and the time to relMSE 0.05 of
wavepath (its default and each --wp-variant), Blender Cycles and Mitsuba 3,
against a high-sample reference, on 2 threads and pinned to one core.

Both modes alternate the renderers A B C A B C within every round, so that a
shared machine's drift hits them alike, give each round a fresh seed, and
begin with a calibration render: pixels that see the light must read 100 in
every renderer, and every renderer's per-channel image means must agree with
wavepath's (throughput) or the reference's (error) within 1 %; otherwise the
output says the comparison is not of equal work. Times are render times
inside each renderer, without process start-up or kernel compilation
(wavepath's profile wall_seconds, Mitsuba's mi.render less Dr.Jit's compile,
Cycles' bpy.ops.render.render); an untimed warm-up render per renderer fills
the kernel caches first. Writes results.md, results.json, convergence.svg
(error mode) and PNG views of the calibration renders into --out-dir.
A benchmark, never a test: CI does not run it (docs/performance.md).
Needs: mitsuba and numpy (pip), Debian's blender and libllvm19
(tools/install-deps.sh --bench).
"""
import argparse
import json
import math
import os
import shlex
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import peers_image  # noqa: E402
import peers_plot  # noqa: E402
import peers_renderers  # noqa: E402

REPOSITORY = Path(__file__).resolve().parent.parent
LIGHT_RADIANCE = 100.0
MEANS_TOLERANCE = 0.01  # the per-channel image means must agree within 1 %
LIGHT_TOLERANCE = 0.001  # pixels that see the light read 100 within 0.1 %
TARGET_REL_MSE = 0.05


def fail(message):
    print(f"peers: error: {message}", file=sys.stderr)
    sys.exit(1)


def load_average():
    with open("/proc/loadavg") as file:
        return " ".join(file.read().split()[:3])


def machine_description():
    model = "unknown CPU"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{model}, {os.cpu_count()} cores"


def parse_list(text, convert, what):
    try:
        values = [convert(v) for v in text.split(",") if v.strip()]
    except ValueError:
        fail(f"{what} must be a comma-separated list, not '{text}'")
    if not values:
        fail(f"{what} is empty")
    return values


# ---------------------------------------------------------------------------
# Calibration: equal work or not


def calibrate(renders, judge_against, label_against, is_reference=False):
    """renders: {renderer label: image}; judge_against: the image whose means
    the others must match (a reference: then each line also gives the
    standard error of the image mean, sqrt(MSE_c / pixels), the pixels'
    errors being independent). Returns (report lines, equal_work)."""
    lines = []
    equal = True
    mask = peers_image.light_pixels(judge_against, LIGHT_RADIANCE)
    target_means = judge_against.reshape(-1, 3).mean(axis=0)
    lines.append(f"calibration against {label_against}: {int(mask.sum())} pixels see only the "
                 f"light; per-channel means {peers_image.triple(target_means)}")
    if mask.sum() == 0:
        lines.append("  no pixel sees only the light: the light reads 100 check cannot run")
        equal = False
    for label, image in renders.items():
        means = image.reshape(-1, 3).mean(axis=0)
        deviation = means / target_means - 1.0
        light = image[mask] if mask.sum() else None
        light_error = float(abs(light / LIGHT_RADIANCE - 1.0).max()) if light is not None else math.nan
        light_ok = light is not None and light_error <= LIGHT_TOLERANCE
        means_ok = bool(abs(deviation).max() <= MEANS_TOLERANCE)
        blocks = peers_image.block_means(image) / peers_image.block_means(judge_against) - 1.0
        noise = ""
        if is_reference:
            pixels = image.shape[0] * image.shape[1]
            mse = ((image - judge_against) ** 2).reshape(-1, 3).mean(axis=0)
            standard_error = (mse / pixels) ** 0.5 / target_means
            noise = "; standard error " + ", ".join(f"{100 * v:.2f} %" for v in standard_error)
            if not means_ok and bool((abs(deviation) <= 3 * standard_error).all()):
                noise += ", so within noise: raise --calibration-spp"
        equal = equal and light_ok and means_ok
        lines.append(f"  {label}: light pixels {float(light.mean()) if light is not None else math.nan:.4f} "
                     f"(largest deviation {light_error * 100:.3f} %, {'ok' if light_ok else 'FAILS'}); "
                     f"means {peers_image.triple(means)}, "
                     f"{', '.join(f'{100 * d:+.2f} %' for d in deviation)}{noise} "
                     f"({'ok' if means_ok else 'FAILS the 1 % check'}); largest deviation of a 4x4 block's "
                     f"mean {100 * float(abs(blocks).max()):.2f} %")
    if not equal:
        lines.append("  NOT EQUAL WORK: the renderers do not compute the same image, "
                     "so the figures below do not compare like with like")
    return lines, equal


# ---------------------------------------------------------------------------
# throughput (#11)


def run_throughput(args, workdir):
    sizes = parse_list(args.sizes, int, "--sizes")
    spp = args.spp_single
    renderers = [peers_renderers.Wavepath(args.wavepath, [], "wavepath", args.scene)]
    for variant in args.wp_variant:
        renderers.append(peers_renderers.Wavepath(args.wavepath, shlex.split(variant),
                                                  f"wavepath {variant}", args.scene))
    baseline = peers_renderers.baseline_binary(args, workdir)
    if baseline:
        renderers.append(peers_renderers.Wavepath(baseline[0], [], f"wavepath {baseline[1]}", args.scene))
    renderers.append(peers_renderers.Mitsuba(args, workdir))
    threads = args.threads

    out = Path(args.out_dir)
    calibration_size = sizes[0]
    print(f"peers: calibration at {calibration_size}x{calibration_size}, {args.calibration_spp} spp",
          flush=True)
    images = {}
    for r in renderers:
        r.warm_up(calibration_size, threads)
        result = r.render(calibration_size, args.calibration_spp, 1, threads, None,
                          workdir / f"calibration-{r.slug}.exr")
        images[r.label] = peers_image.read(result["image"])
        peers_image.write_png(images[r.label], out / f"calibration-{r.slug}.png")
    peers_image.write_row(list(images.values()), out / "calibration-side-by-side.png")
    report, equal = calibrate({k: v for k, v in images.items() if k != renderers[0].label},
                              images[renderers[0].label], renderers[0].label)
    print("\n".join(report), flush=True)

    runs = []
    for size in sizes:
        for r in renderers:
            r.warm_up(size, threads)
        for round_index in range(args.rounds):
            for r in renderers:
                load_before = load_average()
                result = r.render(size, spp, 1000 + round_index, threads, None,
                                  workdir / f"t-{r.slug}-{size}.exr")
                runs.append({"renderer": r.label, "size": size, "spp": spp, "round": round_index,
                             "seconds": result["seconds"], "load_before": load_before,
                             "load_after": load_average(),
                             "samples_per_second": size * size * spp / result["seconds"]})
                print(f"peers: {size}x{size} {spp} spp round {round_index} {r.label}: "
                      f"{result['seconds']:.3f} s (load {load_before})", flush=True)

    rows = []
    for size in sizes:
        reference_seconds = None
        for r in renderers:
            seconds = [x["seconds"] for x in runs if x["renderer"] == r.label and x["size"] == size]
            median = statistics.median(seconds)
            if reference_seconds is None:
                reference_seconds = median
            rows.append({"renderer": r.label, "size": size, "spp": spp,
                         "median_seconds": median, "seconds": seconds,
                         "samples_per_second": size * size * spp / median,
                         "speed_relative_to_wavepath": reference_seconds / median})
    header = (f"hexroom, {spp} spp, {threads} threads each, median of {args.rounds} alternating "
              f"rounds; {machine_description()}; {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}")
    md = [f"<!-- {header} -->", "", "```", *report, "```", "",
          "| size | renderer | median time | samples/s | samples/s, this / wavepath | runs (s) |",
          "| --- | --- | ---: | ---: | ---: | --- |"]
    for row in rows:
        md.append(f"| {row['size']}x{row['size']} | {row['renderer']} | {row['median_seconds']:.3f} s | "
                  f"{row['samples_per_second'] / 1e6:.3f} M | {row['speed_relative_to_wavepath']:.2f} | "
                  f"{' '.join(f'{s:.2f}' for s in row['seconds'])} |")
    loads = [x["load_before"] for x in runs]
    md.append("")
    md.append(f"Load averages (1, 5, 15 min) before each run: first {loads[0]}, last {loads[-1]}.")
    tracing = run_tracing(args, md)
    finish(args, {"mode": "throughput", "header": header, "calibration": report,
                  "equal_work": equal, "rows": rows, "runs": runs, "tracing": tracing,
                  "command": " ".join(shlex.quote(a) for a in sys.argv)}, md)


def run_tracing(args, md):
    """wavepath's intersect and shadow stages against Embree on the scene's rays
    (bench/bvh_vs_embree.cpp --scene); appends its table to md, returns its JSON."""
    binary = Path(args.embree_bench)
    if not binary.is_file():
        note = (f"tracing against Embree skipped: {binary} does not exist (cmake -DWAVEPATH_BUILD_BENCH=ON, "
                "build target wavepath_bench_bvh; bash tools/install-deps.sh --bench)")
        print(f"peers: {note}", flush=True)
        md += ["", note]
        return None
    out = Path(args.out_dir) / "tracing.json"
    command = [str(binary), "--scene", args.scene, "--threads", str(args.threads), "--json", str(out)]
    print(f"peers: {' '.join(shlex.quote(c) for c in command)} (load {load_average()})", flush=True)
    completed = subprocess.run(command, capture_output=True, text=True)
    if completed.returncode != 0:
        fail(f"{binary} failed: {completed.stderr.strip().splitlines()[-1:] or completed.returncode}")
    result = json.loads(out.read_text())[0]
    md += ["", f"Tracing, Mrays/s, best of 3 (wavepath's stage kernels on PoCL; Embree {args.threads} threads, "
           f"its high-quality BVH; load {result['load_start']} to {result['load_end']}; incoherent origins in "
           f"the free space, {result['incoherent_kept']:.1%} of the box's candidates kept):", "",
           "| stage | rays | count | wavepath | Embree 1-ray | Embree 16-ray | wavepath / Embree 16 | "
           "hits vs Embree (same / tie / differ) |",
           "| --- | --- | ---: | ---: | ---: | ---: | ---: | --- |"]
    for t in result["traced"]:
        check = t["check_vs_embree_medium_1"]
        differ = check["t_differs"] + check["other"] + check["hit_miss"]
        md.append(f"| {t['kind']} | {t['rays']} | {t['count']} | {t['wavepath_mrays']:.2f} | "
                  f"{t['embree_high_1_mrays']:.2f} | {t['embree_high_16_mrays']:.2f} | "
                  f"{t['wavepath_mrays'] / t['embree_high_16_mrays']:.2f} | "
                  f"{check['same']} / {check['tie']} / {differ} |")
    return result


# ---------------------------------------------------------------------------
# error per second (#12)


def time_to_target(points, target):
    """points: (seconds, relMSE) per spp. The time at which relMSE reaches
    target, interpolated linearly in log-log between the two points that
    bracket it; past either end, extrapolated from the nearest point along
    relMSE proportional to 1/t (the Monte Carlo rate). Returns (seconds, how)."""
    points = sorted(p for p in points if p[0] > 0 and p[1] > 0)
    for (t0, e0), (t1, e1) in zip(points, points[1:]):
        if (e0 - target) * (e1 - target) <= 0 and e0 != e1:
            f = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0))), "interpolated"
    t, e = points[-1] if points[-1][1] > target else points[0]
    return t * e / target, "extrapolated"


def run_error(args, workdir):
    if not args.reference:
        fail("error mode needs --reference REF.exr (a high-sample wavepath render at "
             "the benchmark's size, e.g. /work/ref/hexroom-256-ref4096.exr)")
    if not Path(args.reference).is_file():
        fail(f"reference '{args.reference}' does not exist")
    reference = peers_image.read(args.reference)
    size = reference.shape[1]
    if reference.shape[0] != size:
        fail(f"the reference is {reference.shape[1]}x{reference.shape[0]}; the hexroom is square")
    spps = parse_list(args.spp, int, "--spp")
    modes = parse_list(args.modes, str, "--modes")
    for m in modes:
        if m not in ("two-threads", "one-core"):
            fail(f"--modes: unknown mode '{m}' (two-threads, one-core)")

    renderers = [peers_renderers.Wavepath(args.wavepath, [], "wavepath", args.scene)]
    for variant in args.wp_variant:
        renderers.append(peers_renderers.Wavepath(args.wavepath, shlex.split(variant),
                                                  f"wavepath {variant}", args.scene))
    renderers.append(peers_renderers.Cycles(args))
    renderers.append(peers_renderers.Mitsuba(args, workdir))

    out = Path(args.out_dir)
    peers_image.write_png(reference, out / "reference.png")
    print(f"peers: calibration at {size}x{size}, {args.calibration_spp} spp, 2 threads", flush=True)
    images = {}
    for r in renderers:
        r.warm_up(size, 2)
        result = r.render(size, args.calibration_spp, 1, 2, None, workdir / f"calibration-{r.slug}.exr")
        images[r.label] = peers_image.read(result["image"])
        peers_image.write_png(images[r.label], out / f"calibration-{r.slug}.png")
    peers_image.write_row([reference] + list(images.values()), out / "calibration-side-by-side.png")
    report, equal = calibrate(images, reference, f"the reference {Path(args.reference).name}", True)
    print("\n".join(report), flush=True)

    runs = []
    for mode in modes:
        threads, core = (2, None) if mode == "two-threads" else (1, args.core)
        for spp in spps:
            for round_index in range(args.rounds):
                seed = 1 + round_index + 1000 * spps.index(spp) + 100000 * modes.index(mode)
                for r in renderers:
                    load_before = load_average()
                    result = r.render(size, spp, seed, threads, core, workdir / f"e-{r.slug}.exr")
                    image = peers_image.read(result["image"])
                    mse, rel_mse = peers_image.errors(image, reference)
                    runs.append({"renderer": r.label, "mode": mode, "spp": spp, "round": round_index,
                                 "seed": seed, "seconds": result["seconds"], "mse": mse,
                                 "rel_mse": rel_mse, "load_before": load_before,
                                 "means": [float(v) for v in image.reshape(-1, 3).mean(axis=0)]})
                    print(f"peers: {mode} {spp} spp round {round_index} {r.label}: "
                          f"{result['seconds']:.3f} s, MSE {mse:.4g}, relMSE {rel_mse:.4g} "
                          f"(load {load_before})", flush=True)

    rows = []
    for mode in modes:
        for spp in spps:
            base = None
            for r in renderers:
                mine = [x for x in runs if x["renderer"] == r.label and x["mode"] == mode and x["spp"] == spp]
                seconds = statistics.fmean(x["seconds"] for x in mine)
                mse = statistics.fmean(x["mse"] for x in mine)
                rel_mse = statistics.fmean(x["rel_mse"] for x in mine)
                row = {"renderer": r.label, "mode": mode, "spp": spp, "rounds": len(mine),
                       "seconds": seconds, "mse": mse, "rel_mse": rel_mse,
                       "efficiency": 1 / (mse * seconds), "rel_efficiency": 1 / (rel_mse * seconds)}
                base = base or row
                row["wavepath_ratio"] = base["efficiency"] / row["efficiency"]
                row["wavepath_rel_ratio"] = base["rel_efficiency"] / row["rel_efficiency"]
                rows.append(row)
    targets = []
    for mode in modes:
        for r in renderers:
            points = [(x["seconds"], x["rel_mse"]) for x in rows if x["renderer"] == r.label and x["mode"] == mode]
            seconds, how = time_to_target(points, TARGET_REL_MSE)
            targets.append({"renderer": r.label, "mode": mode, "seconds": seconds, "how": how})

    header = (f"hexroom {size}x{size}, spp {','.join(map(str, spps))}, {args.rounds} rounds each "
              f"(fresh seed per round, renderers alternating), reference {Path(args.reference).name}; "
              f"{machine_description()}; {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}")
    md = [f"<!-- {header} -->", "", "```", *report, "```", "",
          "Time: mean over rounds; MSE, relMSE: mean over rounds; efficiency 1/(MSE t); "
          "ratio: wavepath's (default) efficiency over this renderer's.", "",
          "| threads | spp | renderer | time | MSE | relMSE | 1/(MSE t) | 1/(relMSE t) "
          "| ratio wavepath/this (MSE) | (relMSE) |",
          "| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for row in rows:
        md.append(f"| {row['mode']} | {row['spp']} | {row['renderer']} | {row['seconds']:.3f} s | "
                  f"{row['mse']:.4g} | {row['rel_mse']:.4g} | {row['efficiency']:.4g} | "
                  f"{row['rel_efficiency']:.4g} | {row['wavepath_ratio']:.2f} | {row['wavepath_rel_ratio']:.2f} |")
    md += ["", f"Time to relMSE {TARGET_REL_MSE} (log-log on the convergence curve):", "",
           "| threads | renderer | seconds | how |", "| --- | --- | ---: | --- |"]
    for t in targets:
        md.append(f"| {t['mode']} | {t['renderer']} | {t['seconds']:.3g} | {t['how']} |")
    loads = [x["load_before"] for x in runs]
    md += ["", f"Load averages (1, 5, 15 min) before the runs: first {loads[0]}, last {loads[-1]}."]
    series = []
    for mode in modes:
        for r in renderers:
            pts = sorted(((x["seconds"], x["rel_mse"], x["spp"]) for x in rows
                          if x["renderer"] == r.label and x["mode"] == mode), key=lambda p: p[2])
            series.append({"label": f"{r.label} ({mode})", "points": pts, "dashed": mode == "one-core"})
    peers_plot.write_svg(out / "convergence.svg", series, f"hexroom {size}x{size}: relMSE against render time",
                         "render time (s)", "relMSE")
    finish(args, {"mode": "error", "header": header, "calibration": report, "equal_work": equal,
                  "rows": rows, "time_to_rel_mse_0_05": targets, "runs": runs,
                  "command": " ".join(shlex.quote(a) for a in sys.argv)}, md)


def finish(args, result, md):
    out = Path(args.out_dir)
    (out / "results.json").write_text(json.dumps(result, indent=1) + "\n")
    (out / "results.md").write_text("\n".join(md) + "\n")
    print("\n".join(md))
    print(f"peers: wrote {out}/results.md, results.json" +
          (", convergence.svg" if result["mode"] == "error" else ""))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog=__doc__.split("\n\n", 1)[1])
    parser.add_argument("mode", choices=["throughput", "error"])
    parser.add_argument("--wavepath", default=str(REPOSITORY / "build" / "wavepath"),
                        help="the wavepath binary under test (default: build/wavepath)")
    parser.add_argument("--scene", default=str(REPOSITORY / "scenes" / "hexroom.json"))
    parser.add_argument("--out-dir", default=str(REPOSITORY / "build" / "peers-out"),
                        help="where results go (default: build/peers-out, which git ignores)")
    parser.add_argument("--rounds", type=int, default=None,
                        help="alternating rounds (default: 3 throughput, 2 error)")
    parser.add_argument("--calibration-spp", type=int, default=256)
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--llvm", default=None,
                        help="libLLVM for Mitsuba's llvm variant (default: $DRJIT_LIBLLVM_PATH, "
                        "else Debian's libLLVM 19 or 16)")
    parser.add_argument("--mitsuba-variant", default="llvm_ad_rgb")
    parser.add_argument("--wp-variant", action="append", default=[],
                        help="wavepath options of a further wavepath run (both modes), written with '=' "
                        "since they begin with '-': --wp-variant='--sampler sobol' (repeatable)")
    group = parser.add_argument_group("throughput")
    group.add_argument("--sizes", default="256,800", help="square image sizes (default: 256,800)")
    group.add_argument("--spp-single", "--throughput-spp", type=int, default=64, dest="spp_single",
                       help="samples per pixel of each throughput render (default: 64)")
    group.add_argument("--threads", type=int, default=2, help="threads of every renderer (default: 2)")
    group.add_argument("--baseline", help="an earlier wavepath commit: built in a git worktree under /tmp")
    group.add_argument("--baseline-binary", help="an earlier wavepath binary")
    group.add_argument("--embree-bench", default=str(REPOSITORY / "build" / "bench" / "wavepath_bench_bvh"),
                       help="the tracing benchmark against Embree (default: build/bench/wavepath_bench_bvh)")
    group = parser.add_argument_group("error")
    group.add_argument("--reference", help="high-sample reference image (.exr) of the hexroom")
    group.add_argument("--spp", default="16,64,256,1024", help="sample counts (default: 16,64,256,1024)")
    group.add_argument("--modes", default="two-threads,one-core",
                       help="two-threads (no pinning) and/or one-core (1 thread, taskset to --core)")
    group.add_argument("--core", type=int, default=0, help="the core of one-core mode (default: 0)")
    args = parser.parse_args()
    if args.rounds is None:
        args.rounds = 3 if args.mode == "throughput" else 2
    if args.rounds < 1 or args.calibration_spp < 1 or args.spp_single < 1:
        fail("--rounds, --calibration-spp and --throughput-spp must be at least 1")
    if not Path(args.wavepath).is_file():
        fail(f"wavepath binary '{args.wavepath}' does not exist (build it, or give --wavepath)")
    if not Path(args.scene).is_file():
        fail(f"scene '{args.scene}' does not exist")
    Path(args.out_dir).mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="wavepath-peers-") as scratch:
        try:
            (run_throughput if args.mode == "throughput" else run_error)(args, Path(scratch))
        except peers_renderers.RendererError as error:
            fail(str(error))


if __name__ == "__main__":
    main()

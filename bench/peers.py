#!/usr/bin/env python3
"""wavepath side by side with its peers on any scene (issues #11, #12 and #34).

    python3 bench/peers.py throughput [--scene S] [--peers mitsuba] [--sizes 256,800] [--spp 64]
                                      [--rounds 3] [--baseline COMMIT | --baseline-binary PATH]
                                      [--wp-variant="--mirror-nee off"]
    python3 bench/peers.py error --reference REF.exr [--scene S] [--peers cycles,mitsuba]
                                 [--spp 16,64,256,1024] [--rounds 2]
                                 [--modes two-threads,one-core] [--wp-variant="--sampler sobol"]
                                 [--baseline COMMIT | --baseline-binary PATH]
    python3 bench/peers.py reference --scene S --size 256 --reference-spp 4096 --out REF.exr
                                     [--reference-renderer mitsuba|wavepath]
    python3 bench/peers.py suite [--size 256] [--spp 16,64] [--rounds 2] [--reference-spp 1024]
                                 [--only hexroom,cornell-bunny,showcase]
    python3 bench/peers.py agree SCENE.xml|SCENE.json [--spp 64] [--seeds 4] [--reference-spp 1024]

throughput: whole-render time and samples/s of wavepath (its default and each
--wp-variant), its peers (default Mitsuba 3 llvm_ad_rgb) and (with
--baseline) an earlier wavepath build, at each size, 2 threads each;
then wavepath's intersect and shadow stages against Embree 1-ray and 16-ray
on the same 4x10^6 incoherent rays of the scene's free space (and its camera,
bounce and light rays), hits checked ray by ray, by build/bench/
wavepath_bench_bvh --scene (built with -DWAVEPATH_BUILD_BENCH=ON; skipped,
saying so, when it is not there).
error: MSE, relMSE, time, samples/s, efficiency 1/(MSE t) and the time to
relMSE 0.05 of wavepath (its default and each --wp-variant) and its peers
(default: Blender Cycles and Mitsuba 3 on the hexroom, Mitsuba 3 elsewhere)
and (with --baseline) an earlier wavepath build, against a long reference,
on 2 threads and pinned to one core.
reference: that long reference, by Mitsuba 3 through export-mitsuba (in
passes of --reference-pass-spp, averaged) or by wavepath.
suite: issue #34's set in one command: error mode (two threads; samples/s
from the same renders) on the hexroom (wavepath's default and --mirror-nee
off), scenes/cornell-bunny.json and scenes/materials/showcase.json (wavepath's
default and --roulette-depth 5, Mitsuba's roulette depth) against
Mitsuba references made once into --reference-dir, then one table of all.
agree: does wavepath render the scene as Mitsuba 3 does? K renders each at
equal samples, means and blocks in combined standard errors, a difference
image (bench/peers_agree.py, which has its own options: agree --help).

Cycles rebuilds the hexroom (bench/peers_cycles.py) and no other scene, so
--peers cycles is refused elsewhere. Both measuring modes alternate the
renderers A B C A B C within every round, so that a shared machine's drift
hits them alike, give each round a fresh seed, and begin with a calibration
render. Where pixels see a light of radiance 100 (the hexroom) those pixels
must read 100 in every renderer, and every renderer's per-channel image means
must agree with wavepath's (throughput) or the reference's (error) within
1 %; in other scenes every renderer's per-channel means and 4x4 block means
must agree within 5 combined standard errors. Otherwise the output says the
comparison is not of equal work. Times are render times
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
HEXROOM = REPOSITORY / "scenes" / "hexroom.json"
PEERS = ("mitsuba", "cycles")
LIGHT_RADIANCE = 100.0
MEANS_TOLERANCE = 0.01  # the per-channel image means must agree within 1 %
LIGHT_TOLERANCE = 0.001  # pixels that see the light read 100 within 0.1 %
STATISTICAL_SIGMAS = 5.0  # elsewhere: means and block means within 5 combined standard errors
TARGET_REL_MSE = 0.05
REFERENCE_SEED = 987654


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


def scene_name(scene):
    return Path(scene).stem


def is_hexroom(scene):
    """Cycles rebuilds the hexroom (bench/peers_cycles.py), no other scene."""
    try:
        return Path(scene).read_bytes() == HEXROOM.read_bytes()
    except OSError:
        return False


def peer_renderers(args, workdir, mode):
    """The peers --peers names, in the order Cycles, Mitsuba. Default: Mitsuba,
    and in error mode on the hexroom Cycles before it (as before --peers)."""
    text = args.peers
    if text is None:
        text = "cycles,mitsuba" if mode == "error" and is_hexroom(args.scene) else "mitsuba"
    names = parse_list(text, str.strip, "--peers")
    for name in names:
        if name not in PEERS:
            fail(f"--peers: unknown renderer '{name}' ({', '.join(PEERS)})")
    if "cycles" in names and not is_hexroom(args.scene):
        fail(f"--peers cycles: Cycles renders only the hexroom (bench/peers_cycles.py rebuilds it), "
             f"not {args.scene}")
    peers = []
    if "cycles" in names:
        peers.append(peers_renderers.Cycles(args))
    if "mitsuba" in names:
        peers.append(peers_renderers.Mitsuba(args, workdir))
    return peers


# ---------------------------------------------------------------------------
# Calibration: equal work or not


def calibrate(renders, judge_against, label_against, is_reference=False):
    """renders: {renderer label: image}; judge_against: the image whose means
    the others must match (a reference: then each line also gives the
    standard error of the image mean, sqrt(MSE_c / pixels), the pixels'
    errors being independent). Where pixels see the light at LIGHT_RADIANCE
    (the hexroom), those pixels must read it and the means agree within 1 %;
    elsewhere the means and 4x4 block means must agree within
    STATISTICAL_SIGMAS combined standard errors (calibrate_by_noise).
    Returns (report lines, equal_work)."""
    mask = peers_image.light_pixels(judge_against, LIGHT_RADIANCE)
    if mask.sum() == 0:
        return calibrate_by_noise(renders, judge_against, label_against)
    lines = []
    equal = True
    target_means = judge_against.reshape(-1, 3).mean(axis=0)
    lines.append(f"calibration against {label_against}: {int(mask.sum())} pixels see only the "
                 f"light; per-channel means {peers_image.triple(target_means)}")
    for label, image in renders.items():
        means = image.reshape(-1, 3).mean(axis=0)
        deviation = means / target_means - 1.0
        light = image[mask]
        light_error = float(abs(light / LIGHT_RADIANCE - 1.0).max())
        light_ok = light_error <= LIGHT_TOLERANCE
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
        lines.append(f"  {label}: light pixels {float(light.mean()):.4f} "
                     f"(largest deviation {light_error * 100:.3f} %, {'ok' if light_ok else 'FAILS'}); "
                     f"means {peers_image.triple(means)}, "
                     f"{', '.join(f'{100 * d:+.2f} %' for d in deviation)}{noise} "
                     f"({'ok' if means_ok else 'FAILS the 1 % check'}); largest deviation of a 4x4 block's "
                     f"mean {100 * float(abs(blocks).max()):.2f} %")
    if not equal:
        lines.append("  NOT EQUAL WORK: the renderers do not compute the same image, "
                     "so the figures below do not compare like with like")
    return lines, equal


def calibrate_by_noise(renders, judge_against, label_against):
    """The check for a scene without pixels that see a light of radiance 100:
    every renderer's per-channel image mean and 4x4 block means must agree
    with judge_against's within STATISTICAL_SIGMAS combined standard errors.
    The combined standard error of a region's mean difference is
    sqrt(sum of (x - r)^2 over its pixels) / pixels: for independent pixels
    whose expectations agree, E[(x - r)^2] is the sum of the two pixels'
    variances, so it needs no renderer's own variance estimate (and a
    reference's noise counts in it)."""
    lines = [f"calibration against {label_against}: no pixel sees a light of radiance "
             f"{LIGHT_RADIANCE:g}, so the check is statistical: per-channel means and 4x4 block means "
             f"within {STATISTICAL_SIGMAS:g} combined standard errors; per-channel means "
             f"{peers_image.triple(judge_against.reshape(-1, 3).mean(axis=0))}"]
    equal = True
    for label, image in renders.items():
        image_z, image_deviation, image_sigma = peers_image.mean_agreement(image, judge_against, 1)
        block_z, _, _ = peers_image.mean_agreement(image, judge_against, 4)
        means_ok = bool(abs(image_z).max() <= STATISTICAL_SIGMAS)
        blocks_ok = bool(abs(block_z).max() <= STATISTICAL_SIGMAS)
        equal = equal and means_ok and blocks_ok
        means = image.reshape(-1, 3).mean(axis=0)
        lines.append(f"  {label}: means {peers_image.triple(means)}, "
                     f"{', '.join(f'{100 * d:+.2f} %' for d in image_deviation.reshape(3))} "
                     f"({', '.join(f'{z:+.1f}' for z in image_z.reshape(3))} sigma; 1 sigma "
                     f"{', '.join(f'{100 * v:.2f} %' for v in image_sigma.reshape(3))}) "
                     f"({'ok' if means_ok else f'FAILS the {STATISTICAL_SIGMAS:g} sigma check'}); "
                     f"farthest 4x4 block {float(abs(block_z).max()):.1f} sigma, "
                     f"{int((abs(block_z) > STATISTICAL_SIGMAS).sum())} of {block_z.size} block channels "
                     f"past {STATISTICAL_SIGMAS:g} ({'ok' if blocks_ok else 'FAILS'})")
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
    renderers += peer_renderers(args, workdir, "throughput")
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
    header = (f"{scene_name(args.scene)}, {spp} spp, {threads} threads each, median of {args.rounds} alternating "
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
        fail("error mode needs --reference REF.exr (a long render at the benchmark's size: "
             "python3 bench/peers.py reference --scene SCENE --size 256 --out REF.exr)")
    if not Path(args.reference).is_file():
        fail(f"reference '{args.reference}' does not exist")
    reference = peers_image.read(args.reference)
    size = reference.shape[1]
    if reference.shape[0] != size:
        fail(f"the reference is {reference.shape[1]}x{reference.shape[0]}; the benchmark's images are square")
    spps = parse_list(args.spp, int, "--spp")
    modes = parse_list(args.modes, str, "--modes")
    for m in modes:
        if m not in ("two-threads", "one-core"):
            fail(f"--modes: unknown mode '{m}' (two-threads, one-core)")

    renderers = [peers_renderers.Wavepath(args.wavepath, [], "wavepath", args.scene)]
    for variant in args.wp_variant:
        renderers.append(peers_renderers.Wavepath(args.wavepath, shlex.split(variant),
                                                  f"wavepath {variant}", args.scene))
    baseline = peers_renderers.baseline_binary(args, workdir)
    if baseline:
        renderers.append(peers_renderers.Wavepath(baseline[0], [], f"wavepath {baseline[1]}", args.scene))
    renderers += peer_renderers(args, workdir, "error")

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
                                 "means": [float(v) for v in image.reshape(-1, 3).mean(axis=0)],
                                 "stages": result.get("stages", {})})
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
                       "efficiency": 1 / (mse * seconds), "rel_efficiency": 1 / (rel_mse * seconds),
                       "samples_per_second": size * size * spp / seconds}
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

    header = (f"{scene_name(args.scene)} {size}x{size}, spp {','.join(map(str, spps))}, {args.rounds} rounds each "
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
    peers_plot.write_svg(out / "convergence.svg", series,
                         f"{scene_name(args.scene)} {size}x{size}: relMSE against render time",
                         "render time (s)", "relMSE")
    return finish(args, {"mode": "error", "header": header, "calibration": report, "equal_work": equal,
                  "rows": rows, "time_to_rel_mse_0_05": targets, "runs": runs,
                  "command": " ".join(shlex.quote(a) for a in sys.argv)}, md)


# ---------------------------------------------------------------------------
# reference: a long render for error mode


def make_reference(args, workdir, scene, size, spp, out):
    """Renders scene at size x size with spp samples per pixel by
    --reference-renderer and writes the image to out (atomically). Mitsuba
    renders it in passes of --reference-pass-spp samples with their own seeds
    (one kernel of size x size x spp lanes would need gigabytes) and the
    passes' mean is the reference; wavepath renders it in one run."""
    out = Path(out)
    start = time.monotonic()
    partial = out.with_name(out.stem + ".partial.exr")
    print(f"peers: reference of {scene} at {size}x{size}, {spp} spp, by {args.reference_renderer} "
          f"(load {load_average()})", flush=True)
    if args.reference_renderer == "wavepath":
        renderer = peers_renderers.Wavepath(args.wavepath, [], "wavepath", scene)
        renderer.render(size, spp, REFERENCE_SEED, args.threads, None, partial)
    else:
        renderer = peers_renderers.Mitsuba(args, workdir, scene)
        if spp % args.reference_pass_spp:
            fail(f"--reference-spp {spp} is not a multiple of --reference-pass-spp {args.reference_pass_spp}")
        passes = spp // args.reference_pass_spp
        result = renderer.render(size, args.reference_pass_spp, REFERENCE_SEED, args.threads, None,
                                 partial, passes)
        print(f"peers: {passes} passes of {args.reference_pass_spp} spp in {result['seconds']:.1f} s "
              f"of rendering", flush=True)
    os.replace(partial, out)
    print(f"peers: wrote {out} ({size}x{size}, {spp} spp, {args.reference_renderer}, "
          f"{time.monotonic() - start:.0f} s)", flush=True)


def run_reference(args, workdir):
    if not args.out:
        fail("reference mode needs --out REF.exr")
    if Path(args.out).suffix != ".exr":
        fail(f"--out '{args.out}' must end in .exr")
    if not Path(args.out).resolve().parent.is_dir():
        fail(f"the folder of --out '{args.out}' does not exist")
    make_reference(args, workdir, args.scene, args.size, args.reference_spp, args.out)


# ---------------------------------------------------------------------------
# suite: issue #34's set in one command


SUITE = [  # (name, scene, wavepath variants)
    ("hexroom", "scenes/hexroom.json", ["--mirror-nee off"]),
    ("cornell-bunny", "scenes/cornell-bunny.json", []),
    ("showcase", "scenes/materials/showcase.json", ["--roulette-depth 5"]),
]


def run_suite(args, workdir):
    """Error mode (two threads) on each scene of SUITE against a Mitsuba
    reference made once and kept in --reference-dir; its renders also give
    samples/s. Ends with one table of every scene."""
    names = [name for name, _, _ in SUITE]
    chosen = parse_list(args.only, str.strip, "--only") if args.only else names
    for name in chosen:
        if name not in names:
            fail(f"--only: unknown scene '{name}' ({', '.join(names)})")
    if args.peers and "cycles" in args.peers and chosen != ["hexroom"]:
        fail("--peers cycles: Cycles renders only the hexroom; give --only hexroom with it")
    out = Path(args.out_dir)
    reference_dir = Path(args.reference_dir)
    reference_dir.mkdir(parents=True, exist_ok=True)
    started = time.monotonic()
    first_load = load_average()
    results = []
    for name, scene, variants in SUITE:
        if name not in chosen:
            continue
        scene = str(REPOSITORY / scene)
        reference = reference_dir / (f"{name}-{args.size}-{args.reference_spp}spp-"
                                     f"{args.reference_renderer}.exr")
        if not reference.is_file():
            make_reference(args, workdir, scene, args.size, args.reference_spp, reference)
        else:
            print(f"peers: reference {reference} is there; kept", flush=True)
        scene_args = argparse.Namespace(**vars(args))
        scene_args.scene = scene
        scene_args.reference = str(reference)
        scene_args.peers = args.peers or "mitsuba"
        scene_args.wp_variant = list(args.wp_variant) + variants
        scene_args.out_dir = str(out / name)
        Path(scene_args.out_dir).mkdir(parents=True, exist_ok=True)
        print(f"peers: suite: {name} ({scene}), load {load_average()}", flush=True)
        results.append((name, run_error(scene_args, workdir)))

    md = suite_markdown(args, results, first_load, load_average(), (time.monotonic() - started) / 60)
    out.mkdir(parents=True, exist_ok=True)
    (out / "suite.md").write_text("\n".join(md) + "\n")
    (out / "suite.json").write_text(json.dumps({"mode": "suite", "command": " ".join(
        shlex.quote(a) for a in sys.argv), "scenes": {name: result for name, result in results}},
        indent=1) + "\n")
    print("\n".join(md))
    print(f"peers: wrote {out}/suite.md, suite.json and each scene's results in {out}/NAME/")


def suite_markdown(args, results, first_load, last_load, minutes):
    """The suite's table of every scene, and wavepath's stages; results: [(name, error mode's result)]."""
    md = [f"<!-- suite: {args.size}x{args.size}, spp {args.spp}, {args.rounds} rounds, two threads, "
          f"references {args.reference_spp} spp by {args.reference_renderer}; {machine_description()}; "
          f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} -->", "",
          f"Error mode at {args.size}x{args.size}, two threads, {args.rounds} alternating rounds per spp; "
          f"references: {args.reference_spp} spp by {args.reference_renderer} (--reference-dir). "
          "samples/s from the same renders. Ratio: wavepath's (default) figure over this renderer's.", "",
          "| scene | spp | renderer | time | samples/s | 1/(MSE t) | 1/(relMSE t) | samples/s ratio "
          "| ratio wavepath/this (MSE) | (relMSE) | equal work |",
          "| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |"]
    for name, result in results:
        base = {}
        for row in result["rows"]:
            base.setdefault(row["spp"], row)
            speed = base[row["spp"]]["samples_per_second"] / row["samples_per_second"]
            md.append(f"| {name} | {row['spp']} | {row['renderer']} | {row['seconds']:.3f} s | "
                      f"{row['samples_per_second'] / 1e6:.3f} M | {row['efficiency']:.4g} | "
                      f"{row['rel_efficiency']:.4g} | {speed:.2f} | {row['wavepath_ratio']:.2f} | "
                      f"{row['wavepath_rel_ratio']:.2f} | {'yes' if result['equal_work'] else 'NO'} |")
    stages = list(dict.fromkeys(stage for _, result in results for x in result["runs"]
                                for stage in x.get("stages", {})))
    md += ["", "wavepath's device seconds per stage (mean over its runs at the largest spp; "
           "POCL's CPU device, --profile-json; a scene rendered by the fused launch plan has "
           "one stage, wave):", "",
           "| scene | renderer | " + " | ".join(stages) + " | wall |",
           "| --- | --- | " + " | ".join("---:" for _ in stages) + " | ---: |"]
    for name, result in results:
        largest = max(row["spp"] for row in result["rows"])
        for label in dict.fromkeys(x["renderer"] for x in result["runs"]):
            mine = [x for x in result["runs"] if x["renderer"] == label and x["spp"] == largest and x["stages"]]
            if not mine:
                continue
            cells = [statistics.fmean(x["stages"].get(stage, 0.0) for x in mine) for stage in stages]
            md.append(f"| {name} ({largest} spp) | {label} | " + " | ".join(f"{c:.2f}" for c in cells) +
                      f" | {statistics.fmean(x['seconds'] for x in mine):.2f} |")
    md += ["", f"Load averages (1, 5, 15 min): {first_load} at the start, {last_load} at the end; "
           f"the suite took {minutes:.1f} min."]
    return md


def finish(args, result, md):
    out = Path(args.out_dir)
    (out / "results.json").write_text(json.dumps(result, indent=1) + "\n")
    (out / "results.md").write_text("\n".join(md) + "\n")
    print("\n".join(md))
    print(f"peers: wrote {out}/results.md, results.json" +
          (", convergence.svg" if result["mode"] == "error" else ""))
    return result


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "agree":
        # Its own options and report (issue #32): bench/peers_agree.py.
        import peers_agree
        sys.argv = [f"{sys.argv[0]} agree"] + sys.argv[2:]
        sys.exit(peers_agree.main())
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog=__doc__.split("\n\n", 1)[1])
    parser.add_argument("mode", choices=["throughput", "error", "reference", "suite"])
    parser.add_argument("--wavepath", default=str(REPOSITORY / "build" / "wavepath"),
                        help="the wavepath binary under test (default: build/wavepath)")
    parser.add_argument("--scene", default=str(HEXROOM),
                        help="the wavepath scene (every mode but suite; default: the hexroom)")
    parser.add_argument("--peers", default=None,
                        help="comma-separated peers: mitsuba, cycles (Cycles only on the hexroom; default: "
                        "mitsuba, and in error mode on the hexroom cycles,mitsuba)")
    parser.add_argument("--out-dir", default=str(REPOSITORY / "build" / "peers-out"),
                        help="where results go (default: build/peers-out, which git ignores)")
    parser.add_argument("--rounds", type=int, default=None,
                        help="alternating rounds (default: 3 throughput, 2 error)")
    parser.add_argument("--calibration-spp", type=int, default=None,
                        help="samples per pixel of the calibration renders (default: 256, suite 64)")
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
    group.add_argument("--baseline", help="an earlier wavepath commit: built in a git worktree "
                       "under /tmp (throughput and error modes)")
    group.add_argument("--baseline-binary", help="an earlier wavepath binary (throughput and error modes)")
    group.add_argument("--embree-bench", default=str(REPOSITORY / "build" / "bench" / "wavepath_bench_bvh"),
                       help="the tracing benchmark against Embree (default: build/bench/wavepath_bench_bvh)")
    group = parser.add_argument_group("error")
    group.add_argument("--reference", help="high-sample reference image (.exr) of the hexroom")
    group.add_argument("--spp", default=None, help="sample counts (default: 16,64,256,1024; suite 16,64)")
    group.add_argument("--modes", default=None,
                       help="two-threads (no pinning) and/or one-core (1 thread, taskset to --core)")
    group.add_argument("--core", type=int, default=0, help="the core of one-core mode (default: 0)")
    group = parser.add_argument_group("reference and suite")
    group.add_argument("--size", type=int, default=256, help="square image size (default: 256)")
    group.add_argument("--reference-spp", type=int, default=None,
                       help="samples per pixel of the reference (default: 4096, suite 1024)")
    group.add_argument("--reference-renderer", choices=["mitsuba", "wavepath"], default="mitsuba",
                       help="who renders the reference (default: mitsuba, through export-mitsuba)")
    group.add_argument("--reference-pass-spp", type=int, default=64,
                       help="Mitsuba renders the reference in passes of this many spp (default: 64)")
    group.add_argument("--out", help="reference: the EXR to write")
    group.add_argument("--reference-dir", default=str(REPOSITORY / "build" / "peers-references"),
                       help="suite: where references are made once and kept (default: build/peers-references)")
    group.add_argument("--only", help="suite: a comma-separated subset of hexroom, cornell-bunny, showcase")
    args = parser.parse_args()
    suite = args.mode == "suite"
    if args.rounds is None:
        args.rounds = 3 if args.mode == "throughput" else 2
    if args.calibration_spp is None:
        args.calibration_spp = 64 if suite else 256
    if args.spp is None:
        args.spp = "16,64" if suite else "16,64,256,1024"
    if args.modes is None:
        args.modes = "two-threads" if suite else "two-threads,one-core"
    if args.reference_spp is None:
        args.reference_spp = 1024 if suite else 4096
    if args.rounds < 1 or args.calibration_spp < 1 or args.spp_single < 1:
        fail("--rounds, --calibration-spp and --throughput-spp must be at least 1")
    if args.size < 1 or args.reference_spp < 1 or args.reference_pass_spp < 1:
        fail("--size, --reference-spp and --reference-pass-spp must be at least 1")
    if not Path(args.wavepath).is_file():
        fail(f"wavepath binary '{args.wavepath}' does not exist (build it, or give --wavepath)")
    if not Path(args.scene).is_file():
        fail(f"scene '{args.scene}' does not exist")
    Path(args.out_dir).mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="wavepath-peers-") as scratch:
        try:
            {"throughput": run_throughput, "error": run_error, "reference": run_reference,
             "suite": run_suite}[args.mode](args, Path(scratch))
        except peers_renderers.RendererError as error:
            fail(str(error))


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Times loading a big binary PLY scene: wavepath against Mitsuba 3 (issue #32,
"Load speed"; docs/mitsuba-import.md). Never a test.

One Mitsuba XML scene (a perspective sensor, a 16x16 hdrfilm, the PLY mesh
with a diffuse BSDF, a constant sky) is loaded, alternating, N rounds, each
contender in a fresh process:

  wavepath   `wavepath render scene.xml --spp 1 --quiet`: parse the XML and
             the PLY, flatten to float32, build the hierarchy, open the device,
             build the kernels (from wavepath's program cache, warmed by a
             first run that is not counted), upload, 1 sample at 16x16, write
             the EXR. Everything a render does before its first sample, and
             a few milliseconds more.
  mitsuba    `mi.load_file(scene.xml)` in `python3`, per variant (scalar_rgb,
             llvm_ad_rgb): the PLY read and the scene's acceleration structure
             built. `load s` is load_file alone; `wall s` the whole child
             process, Python's start and `import mitsuba` included.

Each child's peak resident memory and CPU time (user + system, all its
threads: less sensitive than the wall time to a shared machine's load) come
from os.wait4. The load average (`uptime`) is printed before and after.
--baseline times a second wavepath binary alongside (e.g. main's build).

Usage:
    python3 bench/ply_load.py [--ply FILE] [--rounds 3] [--wavepath build/wavepath] [--baseline B]
                              [--variants scalar_rgb llvm_ad_rgb] [--work DIR]

Without --ply it writes the 1,002,252-triangle displaced sphere of
scenes/million.json (tools/make_displaced_sphere.py, 19 MB) into --work.
Mitsuba is a bench-only dependency (pip install mitsuba); its llvm variant
needs libLLVM (DRJIT_LIBLLVM_PATH, else the newest /usr/lib/x86_64-linux-gnu/libLLVM-*.so).
"""

import argparse
import glob
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

SCENE = """<scene version="3.0.0">
    <integrator type="path"/>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world">
            <lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/>
        </transform>
        <sampler type="independent"><integer name="sample_count" value="1"/></sampler>
        <film type="hdrfilm">
            <integer name="width" value="16"/>
            <integer name="height" value="16"/>
        </film>
    </sensor>
    <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
    <shape type="ply">
        <string name="filename" value="{ply}"/>
        <bsdf type="diffuse"/>
    </shape>
</scene>
"""

MITSUBA_CHILD = """
import sys, time
import mitsuba as mi
mi.set_variant(sys.argv[1])
start = time.perf_counter()
scene = mi.load_file(sys.argv[2])
print(time.perf_counter() - start)
"""


def timed(command, env=None):
    """(wall seconds, CPU seconds, peak RSS kB, stdout) of `command`, run once."""
    start = time.perf_counter()
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(read)
        os.dup2(write, 1)
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, 2)
        os.execvpe(command[0], command, env or os.environ)
    os.close(write)
    chunks = []
    while True:
        chunk = os.read(read, 65536)
        if not chunk:
            break
        chunks.append(chunk)
    os.close(read)
    _, status, usage = os.wait4(pid, 0)
    wall = time.perf_counter() - start
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"ply_load: {' '.join(command)} failed (status {status}); run it by hand to see why")
    return wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss, b"".join(chunks).decode()


def uptime():
    return subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--ply", help="the mesh (default: write the 10^6-triangle sphere)")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--wavepath", default=os.path.join(ROOT, "build", "wavepath"))
    parser.add_argument("--baseline", help="another wavepath binary, timed alongside (e.g. main's)")
    parser.add_argument("--variants", nargs="*", default=["scalar_rgb", "llvm_ad_rgb"],
                        help="Mitsuba variants (none: wavepath alone)")
    parser.add_argument("--work", help="folder for the scene and outputs (default: a temporary one)")
    args = parser.parse_args()
    work = args.work or tempfile.mkdtemp(prefix="ply-load-")
    os.makedirs(work, exist_ok=True)
    ply = os.path.abspath(args.ply) if args.ply else os.path.join(work, "sphere-1m.ply")
    if not os.path.exists(ply):
        subprocess.run([sys.executable, os.path.join(ROOT, "tools", "make_displaced_sphere.py"), ply],
                       check=True)
    scene = os.path.join(work, "scene.xml")
    with open(scene, "w") as f:
        f.write(SCENE.format(ply=ply))

    env = dict(os.environ)
    if "DRJIT_LIBLLVM_PATH" not in env:
        llvm = sorted(glob.glob("/usr/lib/x86_64-linux-gnu/libLLVM-*.so"))
        if llvm:
            env["DRJIT_LIBLLVM_PATH"] = llvm[-1]
    mitsuba_script = os.path.join(work, "mitsuba_load.py")
    with open(mitsuba_script, "w") as f:
        f.write(MITSUBA_CHILD)

    out = os.path.join(work, "wavepath.exr")
    contenders = {"wavepath": [args.wavepath, "render", scene, "--spp", "1", "--quiet",
                               "--out", out]}
    if args.baseline:
        contenders["wavepath baseline"] = [args.baseline] + contenders["wavepath"][1:]
    for variant in args.variants:
        contenders["mitsuba " + variant] = [sys.executable, mitsuba_script, variant, scene]

    print(f"scene: {scene} ({os.path.getsize(ply):,} bytes of PLY: {ply})")
    print(f"before: {uptime()}")
    # Not counted: wavepath's program cache and Mitsuba's first import
    # (its Python bytecode, Dr.Jit's kernel cache) are warmed.
    for name, command in contenders.items():
        timed(command, env)
    results = {name: [] for name in contenders}
    names = list(contenders)
    for r in range(args.rounds):
        order = names[r % len(names):] + names[:r % len(names)]  # alternating starts
        for name in order:
            wall, cpu, rss, text = timed(contenders[name], env)
            load = float(text.strip().splitlines()[-1]) if name.startswith("mitsuba") else None
            results[name].append((wall, cpu, rss, load))
            print(f"  round {r + 1}: {name:22s} wall {wall:7.2f} s, CPU {cpu:7.2f} s"
                  + (f", load {load:6.2f} s" if load is not None else "")
                  + f", peak RSS {rss:,} kB", flush=True)
    print(f"after: {uptime()}")
    print()
    print("| contender | rounds | wall s, median (min-max) | CPU s (user + sys), median "
          "| load s, median | peak RSS kB, median |")
    print("| --- | ---: | --- | ---: | ---: | ---: |")
    for name, runs in results.items():
        walls = [w for w, _, _, _ in runs]
        cpus = [c for _, c, _, _ in runs]
        loads = [l for _, _, _, l in runs if l is not None]
        rss = statistics.median(r for _, _, r, _ in runs)
        print(f"| {name} | {len(runs)} | {statistics.median(walls):.2f} "
              f"({min(walls):.2f}-{max(walls):.2f}) | {statistics.median(cpus):.2f} | "
              + (f"{statistics.median(loads):.2f}" if loads else "-")
              + f" | {rss:,.0f} |")


if __name__ == "__main__":
    main()

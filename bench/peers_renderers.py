"""The renderers bench/peers.py runs, one process per render so that each
gets its own thread count and CPU pinning. Each render returns its render
time (inside the renderer: no process start-up, no kernel compilation) and
the path of its float EXR."""
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPOSITORY = HERE.parent
# Dr.Jit 1.5 (Mitsuba 3.9) emits llvm.minimum, which LLVM 16's x86 back end
# cannot select ("LLVM ERROR: Cannot select: fminimum"), so 19 comes first.
LLVM_CANDIDATES = ["/usr/lib/x86_64-linux-gnu/libLLVM-19.so", "/usr/lib/llvm-19/lib/libLLVM.so",
                   "/usr/lib/x86_64-linux-gnu/libLLVM-16.so", "/usr/lib/llvm-16/lib/libLLVM-16.so"]


class RendererError(Exception):
    pass


def pinning(core):
    """taskset's prefix for one core, or nothing."""
    return [] if core is None else ["taskset", "-c", str(core)]


def run(command, env=None, what="render"):
    completed = subprocess.run([str(c) for c in command], env=env, capture_output=True, text=True)
    if completed.returncode != 0:
        lines = (completed.stderr.strip() or completed.stdout.strip() or "no output").splitlines()
        raise RendererError(f"{what} failed (exit {completed.returncode}): {lines[-1]}")
    return completed.stdout


class Wavepath:
    def __init__(self, binary, options, label, scene):
        self.binary = str(binary)
        self.scene = scene
        self.options = list(options)
        self.label = label
        self.slug = re.sub(r"[^A-Za-z0-9]+", "-", label).strip("-")
        help_text = run([self.binary, "render", "--help"], what=f"{label} --help")
        self.has_profile_json = "--profile-json" in help_text

    def render(self, size, spp, seed, threads, core, out):
        profile = Path(out).with_suffix(".profile.json")
        command = pinning(core) + [self.binary, "render", self.scene, "--width", size, "--height", size,
                                   "--spp", spp, "--seed", seed, "-q", "--out", out] + self.options
        if self.has_profile_json:
            command += ["--profile-json", profile]
        env = dict(os.environ, POCL_MAX_PTHREAD_COUNT=str(threads))
        stdout = run(command, env, f"{self.label} render")
        stages = {}
        if self.has_profile_json:
            report = json.loads(profile.read_text())
            seconds = report["wall_seconds"]
            stages = {s["stage"]: s["device_seconds"] for s in report.get("stages", [])}
        else:  # older builds: the "rendered ..." line's samples/s
            match = re.search(r"([0-9.e+]+) samples/s", stdout)
            if not match:
                raise RendererError(f"{self.label}: no samples/s in its output")
            seconds = size * size * spp / float(match.group(1))
        return {"seconds": seconds, "image": out, "stages": stages}

    def warm_up(self, size, threads):
        """Fills the program cache and PoCL's kernel cache (docs/convergence.md)."""
        self.render(size, 1, 0, threads, None, Path(os.environ.get("TMPDIR", "/tmp")) /
                    f"wavepath-peers-warm-{os.getpid()}-{self.slug}.exr")


class Mitsuba:
    """Mitsuba 3 on the scene as `wavepath export-mitsuba` writes it."""

    def __init__(self, args, workdir, scene=None):
        self.args = args
        self.scene_file = scene or args.scene
        self.workdir = Path(workdir)
        self.variant = args.mitsuba_variant
        self.label = f"Mitsuba {self.variant}"
        self.slug = "mitsuba"
        self.env = dict(os.environ)
        if self.variant.startswith("llvm"):
            library = args.llvm or os.environ.get("DRJIT_LIBLLVM_PATH") or next(
                (c for c in LLVM_CANDIDATES if Path(c).exists()), None)
            if not library:
                raise RendererError("no libLLVM for Mitsuba's llvm variant: apt-get install libllvm19 "
                                    "(tools/install-deps.sh --bench) or give --llvm")
            self.env["DRJIT_LIBLLVM_PATH"] = library
        self.scenes = {}

    def scene(self, size):
        if size not in self.scenes:
            xml = self.workdir / f"{Path(self.scene_file).stem}-{size}.xml"
            run([self.args.wavepath, "export-mitsuba", self.scene_file, xml, "--width", size,
                 "--height", size, "--spp", 1], what="wavepath export-mitsuba")
            self.scenes[size] = xml
        return self.scenes[size]

    def render(self, size, spp, seed, threads, core, out, passes=1):
        command = pinning(core) + [sys.executable, HERE / "peers_mitsuba.py", self.scene(size),
                                   "--spp", spp, "--seed", seed, "--threads", threads,
                                   "--variant", self.variant, "--out", out, "--passes", passes]
        stdout = run(command, self.env, "Mitsuba render")
        result = json.loads(stdout.strip().splitlines()[-1])
        return {"seconds": result["render_seconds"], "image": out}

    def warm_up(self, size, threads):
        """Fills Dr.Jit's kernel cache (~/.drjit); the kernel does not depend on spp or seed."""
        self.render(size, 1, 0, threads, None, self.workdir / "mitsuba-warm.exr")


class Cycles:
    """Blender Cycles on the scene as bench/peers_cycles.py builds it."""

    def __init__(self, args, scene=None):
        self.args = args
        self.scene_file = scene or args.scene
        self.label = "Cycles"
        self.slug = "cycles"
        if shutil.which(args.blender) is None and not Path(args.blender).is_file():
            raise RendererError(f"no '{args.blender}': apt-get install blender "
                                "(tools/install-deps.sh --bench) or give --blender")

    def render(self, size, spp, seed, threads, core, out):
        command = pinning(core) + [self.args.blender, "-b", "--factory-startup", "-noaudio",
                                   "--python-exit-code", 1, "--python", HERE / "peers_cycles.py", "--",
                                   "--scene", self.scene_file, "--width", size, "--height", size,
                                   "--spp", spp, "--seed", seed, "--threads", threads, "--out", out]
        stdout = run(command, what="Cycles render")
        for line in stdout.splitlines():
            if line.startswith("peers_cycles "):
                return {"seconds": json.loads(line[len("peers_cycles "):])["render_seconds"], "image": out}
        raise RendererError("Cycles render printed no result line")

    def warm_up(self, size, threads):
        pass  # Cycles' CPU kernels are compiled in


def baseline_binary(args, workdir):
    """(binary, label) of the earlier build, or None: --baseline-binary as
    given, or --baseline COMMIT built (target wavepath only) in a git worktree
    /tmp/wavepath-baseline-COMMIT, reused when it is there."""
    if args.baseline_binary:
        if not Path(args.baseline_binary).is_file():
            raise RendererError(f"baseline binary '{args.baseline_binary}' does not exist")
        return args.baseline_binary, Path(args.baseline_binary).name
    if not args.baseline:
        return None
    commit = run(["git", "-C", REPOSITORY, "rev-parse", "--short", args.baseline + "^{commit}"],
                 what=f"git rev-parse {args.baseline}").strip()
    tree = Path(f"/tmp/wavepath-baseline-{commit}")
    binary = tree / "build" / "wavepath"
    if not binary.is_file():
        if not tree.exists():
            run(["git", "-C", REPOSITORY, "worktree", "add", "--detach", tree, commit],
                what="git worktree add")
        launcher = ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"] if shutil.which("ccache") else []
        print(f"peers: building wavepath {commit} in {tree} (target wavepath)", flush=True)
        run(["cmake", "-S", tree, "-B", tree / "build", "-DCMAKE_BUILD_TYPE=Release"] + launcher,
            what="cmake (baseline)")
        run(["cmake", "--build", tree / "build", "-j2", "--target", "wavepath"], what="build (baseline)")
    return binary, commit

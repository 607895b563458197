"""What runs on a worker: one part, rendered by that machine's raytracer.

The task writes the bundle into a private folder, runs `raytracer` on it
with the part's sample range, tile and frame, and returns the part's EXR
(whose alpha holds each pixel's sample count) through the object store.
Failures are of two kinds: the raytracer's own error (a broken scene, a
missing file: the same on any machine, so RenderFailed, never retried) and
a raytracer killed from outside (RaytracerCrashed, retried elsewhere by Ray
like a worker that died).
"""

from __future__ import annotations

import ctypes
import functools
import os
import re
import shutil
import signal
import socket
import subprocess
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

from rtfarm.bundle import Bundle, unpack
from rtfarm.errors import FarmError
from rtfarm.plan import Part
from rtfarm.raytracer import find_raytracer, last_error_line

_PROGRESS = re.compile(r"^progress\s+(\d+)%")
_SUMMARY = re.compile(r"^rendered (\d+)x(\d+) at (\d+) spp in ([0-9.]+) s")
_PR_SET_PDEATHSIG = 1
_FOLDER_PREFIX = "rtfarm-part-"  # + the worker's pid: see _remove_orphans


class RenderFailed(Exception):
    """The raytracer refused the part (exit status 1 or 2): a retry cannot fix it."""


class RaytracerCrashed(Exception):
    """The raytracer was killed or vanished: Ray retries the part."""


@dataclass(frozen=True)
class RenderJob:
    """What every part of one render shares."""

    raytracer: str | None  # --raytracer, resolved on each worker (None: its default)
    args: list[str]  # options every part gets: --spp, --size, --seed, ...


@dataclass
class PartResult:
    exr: bytes
    seconds: float  # the raytracer's wall time, start-up included
    pixel_samples: float  # pixels rendered x samples each
    node: str
    warnings: list[str] = field(default_factory=list)
    # The task's span on the worker's clock (time.time()): what the farm adds
    # around the raytracer (bench/run-farm.sh).
    started: float = 0.0
    finished: float = 0.0


def _die_with_parent() -> None:
    """In the raytracer's child process: a worker killed mid-render takes its
    raytracer along instead of leaving it rendering for nobody."""
    libc = ctypes.CDLL("libc.so.6", use_errno=True)
    libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL)


@functools.lru_cache(maxsize=4)
def _vulkan_gpus(raytracer: str) -> tuple[str, ...]:
    """The device numbers of the machine's Vulkan GPUs (asked once per worker)."""
    listing = subprocess.run(
        [raytracer, "--device", "list"], capture_output=True, text=True, check=False
    ).stdout
    return tuple(
        line.split(":", 1)[0]
        for line in listing.splitlines()
        if re.match(r"^\d+: ", line) and "(CPU," not in line
    )


def _gpu_device_args(raytracer: str) -> list[str]:
    """--device N for the GPU Ray gave this task: its position among the
    machine's Vulkan GPUs (both list them in PCI order); none without one."""
    import ray

    gpu_ids = ray.get_gpu_ids()
    if not gpu_ids:
        return []
    gpus = _vulkan_gpus(raytracer)
    position = int(gpu_ids[0])
    return ["--device", gpus[position]] if position < len(gpus) else []


class _Messages:
    """Reads the raytracer's stderr: progress, summary, warnings; names the
    user's files instead of the task's private copies."""

    def __init__(self, part: Part, board, replacements: dict[str, str]):
        self.part = part
        self.board = board
        self.replacements = replacements
        self.lines: list[str] = []
        self.pixel_samples = 0.0

    def user_text(self, line: str) -> str:
        for private, shown in self.replacements.items():
            line = line.replace(private, shown)
        return line

    def read(self, line: str) -> None:
        line = self.user_text(line.rstrip("\n"))
        self.lines.append(line)
        if match := _PROGRESS.match(line):
            self.report(int(match.group(1)) / 100.0)
        elif match := _SUMMARY.match(line):
            width, height, samples = (int(match.group(i)) for i in (1, 2, 3))
            self.pixel_samples = width * height * self.part.pixel_share * samples

    def report(self, fraction: float) -> None:
        if self.board is None:
            return
        try:
            self.board.report.remote(self.part.index, fraction)
        except Exception:  # progress is a nicety; the render goes on without it
            self.board = None

    def warnings(self) -> list[str]:
        return [line for line in self.lines if line.startswith("warning: ")]


def _command(
    raytracer: str, scene: Path, output: Path, job: RenderJob, part: Part, camera_path: Path | None
) -> list[str]:
    command = [raytracer, str(scene), str(output), *job.args, *part.raytracer_args()]
    if camera_path:
        command += ["--camera-path", str(camera_path)]
    return command + _gpu_device_args(raytracer)


def _run(command: list[str], messages: _Messages) -> int:
    try:
        process = subprocess.Popen(
            command,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
            preexec_fn=_die_with_parent,
        )
    except OSError as error:
        raise RenderFailed(
            f"{command[0]}: cannot run on {socket.gethostname()}: {error.strerror}"
        ) from None
    for line in process.stderr:
        messages.read(line)
    return process.wait()


def _remove_orphans() -> None:
    """Part folders of workers that were killed (and so never removed theirs)."""
    for folder in Path(tempfile.gettempdir()).glob(f"{_FOLDER_PREFIX}*-*"):
        owner = folder.name[len(_FOLDER_PREFIX) :].split("-", 1)[0]
        if owner.isdigit() and not Path(f"/proc/{owner}").exists():
            shutil.rmtree(folder, ignore_errors=True)


def _write_inputs(bundle: Bundle, folder: Path) -> tuple[Path, Path | None, dict[str, str]]:
    """The bundle's files in `folder`: the scene's path, the camera path's,
    and how their private paths are shown to the user."""
    tree = folder / "scene"
    scene = unpack(bundle, tree)
    shown = {f"{tree}/": bundle.display_prefix}
    camera_path = None
    if bundle.camera_path is not None:
        camera_path = folder / "camera-path.txt"
        camera_path.write_bytes(bundle.camera_path)
        shown[str(camera_path)] = bundle.camera_path_name
    return scene, camera_path, shown


def _check_exit(status: int, part: Part, messages: _Messages, output: Path) -> None:
    """RaytracerCrashed (retried) for a raytracer killed from outside,
    RenderFailed (not retried) for one that refused the part."""
    node = socket.gethostname()
    if status < 0:
        name = signal.Signals(-status).name if -status in signal.valid_signals() else -status
        raise RaytracerCrashed(f"{part.describe()}: raytracer killed by signal {name} on {node}")
    if status != 0:
        raise RenderFailed(last_error_line("\n".join(messages.lines)))
    if not output.is_file():
        raise RaytracerCrashed(f"{part.describe()}: raytracer wrote no image on {node}")


def render_part(bundle: Bundle, job: RenderJob, part: Part, board=None) -> PartResult:
    """The Ray task: renders `part` of the bundle's scene; its EXR bytes."""
    started = time.time()
    try:
        raytracer = find_raytracer(job.raytracer)
    except FarmError as error:
        raise RenderFailed(str(error)) from None
    _remove_orphans()
    with tempfile.TemporaryDirectory(prefix=f"{_FOLDER_PREFIX}{os.getpid()}-") as folder:
        scene, camera_path, shown = _write_inputs(bundle, Path(folder))
        output = Path(folder) / "part.exr"
        messages = _Messages(part, board, shown)
        messages.report(0.0)  # running, before the raytracer's first line
        start = time.monotonic()
        status = _run(_command(raytracer, scene, output, job, part, camera_path), messages)
        seconds = time.monotonic() - start
        _check_exit(status, part, messages, output)
        exr = output.read_bytes()
    node = socket.gethostname()
    return PartResult(
        exr, seconds, messages.pixel_samples, node, messages.warnings(), started, time.time()
    )

"""rtfarm render and rtfarm animate, from parsed arguments to files.

Input is checked before the cluster is asked for anything; a failure
leaves no output file (the raytracer writes every image atomically, the
parts live in a private temporary folder, the preview is removed).
"""

from __future__ import annotations

import math
import os
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

from rtfarm import farm
from rtfarm.bundle import Bundle, make_bundle, scene_defaults
from rtfarm.errors import FarmError
from rtfarm.merger import ImageMerger
from rtfarm.plan import Part, default_tasks, plan_animation, plan_still, tiles_for
from rtfarm.progress import ProgressLine
from rtfarm.raytracer import find_raytracer, frame_count
from rtfarm.worker import PartResult, RenderJob

IMAGE_FORMATS = (".png", ".jpg", ".jpeg", ".ppm", ".exr", ".hdr")


def _check_format(path: Path) -> None:
    if path.suffix.lower() not in IMAGE_FORMATS:
        raise FarmError(f"{path}: unsupported output format (use .png, .jpg, .ppm, .exr or .hdr)")


def _check_image_path(path: Path) -> None:
    _check_format(path)
    folder = path.parent if str(path.parent) else Path(".")
    if not folder.is_dir():
        raise FarmError(f"{path}: folder {folder} does not exist")


def _render_args(arguments, spp: int) -> list[str]:
    """The raytracer options every part of this render gets."""
    args = ["--spp", str(spp)]
    if arguments.size:
        args += ["--size", "{}x{}".format(*arguments.size)]
    for flag, value in (
        ("--seed", arguments.seed),
        ("--sampler", arguments.sampler),
        ("--shading", arguments.shading),
        ("--conventions", arguments.conventions),
        ("--mode", arguments.mode),
        ("--bounces", arguments.bounces),
        ("--exposure", arguments.exposure),
        ("--clamp-indirect", arguments.clamp_indirect),
        ("--light-samples", arguments.light_samples),
        ("--light-split", arguments.light_split),
        ("--accel", arguments.accel),
    ):
        if value is not None:
            args += [flag, repr(value) if isinstance(value, float) else str(value)]
    return args


def _remote_raytracer(explicit: str | None) -> str | None:
    """--raytracer as the workers should read it: a path made absolute (the
    same on every node), a bare name looked up on each node's PATH."""
    if explicit and os.sep in explicit:
        return os.path.abspath(explicit)
    return explicit


def _cluster_options(arguments) -> farm.ClusterOptions:
    return farm.ClusterOptions(
        address=arguments.address,
        gpus_per_task=arguments.gpus_per_task,
        cpus_per_task=arguments.cpus_per_task,
        max_retries=arguments.max_retries,
    )


class _Warnings:
    """The scene's warnings, printed once however many parts report them."""

    def __init__(self):
        self.seen: set[str] = set()

    def show(self, result: PartResult) -> None:
        for warning in result.warnings:
            if warning not in self.seen:
                self.seen.add(warning)
                sys.stderr.write(warning + "\n")


class _Preview:
    """OUT.preview.png, merged from the parts so far once every tile has some
    (at most every `interval` seconds); removed when the render ends."""

    def __init__(
        self,
        merger: ImageMerger,
        path: Path | None,
        tiles: int,
        interval: float,
        scene: str,
        conventions: str | None,
    ):
        self.merger = merger
        self.path = path
        self.tiles = tiles
        self.interval = interval
        self.scene = scene
        self.conventions = conventions
        self.covered: set = set()
        self.written_at: float | None = None

    def part_done(self, part: Part) -> None:
        self.covered.add(part.region)
        now = time.monotonic()
        if self.path is None or len(self.covered) < self.tiles:
            return
        if self.written_at is not None and now - self.written_at < self.interval:
            return
        self.merger.write(self.path, self.scene, self.conventions)
        self.written_at = now

    def remove(self) -> None:
        if self.path is not None and self.written_at is not None:
            self.path.unlink(missing_ok=True)


def _preview_path(arguments, output: Path) -> Path | None:
    if arguments.no_preview:
        return None
    path = Path(arguments.preview) if arguments.preview else output.with_suffix(".preview.png")
    _check_image_path(path)
    if path.resolve() == output.resolve():
        raise FarmError(f"--preview {path}: the preview cannot be the output")
    return path


def _prepare(arguments, camera_path: str | None = None) -> tuple[str, Bundle, int]:
    """The driver's raytracer (for merging), the bundle and the sample count."""
    raytracer = find_raytracer(arguments.raytracer)
    bundle = make_bundle(arguments.scene, camera_path)
    spp = arguments.spp or scene_defaults(bundle).spp
    return raytracer, bundle, spp


def _run(
    bundle: Bundle, arguments, spp: int, options: farm.ClusterOptions, parts: list[Part], on_result
) -> None:
    progress = ProgressLine(parts, enabled=not arguments.quiet)
    job = RenderJob(
        raytracer=_remote_raytracer(arguments.raytracer), args=_render_args(arguments, spp)
    )
    warnings = _Warnings()

    def handle(part: Part, result: PartResult) -> None:
        warnings.show(result)
        on_result(part, result)

    try:
        farm.PartRunner(bundle, job, options, progress).run(parts, handle)
        progress.show({}, final=True)
    finally:
        progress.close()


def render(arguments) -> int:
    output = Path(arguments.output)
    _check_image_path(output)
    preview_path = _preview_path(arguments, output)
    raytracer, bundle, spp = _prepare(arguments)
    defaults = scene_defaults(bundle)
    width, height = arguments.size or (defaults.width, defaults.height)
    options = _cluster_options(arguments)
    farm.connect(options.address)
    try:
        tasks = arguments.tasks or default_tasks(farm.worker_slots(options))
        tiles = arguments.tiles or tiles_for(tasks, spp)
        parts = plan_still(spp, tasks, tiles, width, height)
        with tempfile.TemporaryDirectory(prefix="rtfarm-") as folder:
            merger = ImageMerger(raytracer, Path(folder), "image")
            preview = _Preview(
                merger,
                preview_path,
                tiles,
                arguments.preview_every,
                arguments.scene,
                arguments.conventions,
            )

            def add(part: Part, result: PartResult) -> None:
                merger.add(result.exr)
                preview.part_done(part)

            try:
                _run(bundle, arguments, spp, options, parts, add)
                merger.write(output, arguments.scene, arguments.conventions)
            finally:
                preview.remove()
    finally:
        farm.disconnect()
    return 0


def _frame_names(arguments) -> None:
    try:
        name = arguments.name % 0
    except (TypeError, ValueError):
        raise FarmError(f"--name {arguments.name}: needs one %d for the frame number") from None
    if name == arguments.name % 1:
        raise FarmError(f"--name {arguments.name}: needs one %d for the frame number")
    _check_format(Path(arguments.output_dir) / name)


def _frames(arguments, raytracer: str) -> list[int]:
    total = frame_count(raytracer, arguments.camera_path)
    if total == 0:
        raise FarmError(f"{arguments.camera_path}: the camera path has no frames")
    first, end = arguments.frames or (0, total)
    if end > total:
        raise FarmError(f"--frames {first}:{end}: {arguments.camera_path} has {total} frame(s)")
    return list(range(first, end))


def _output_dir(arguments) -> Path:
    folder = Path(arguments.output_dir)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise FarmError(f"{folder}: cannot make the output folder: {error.strerror}") from None
    _check_image_path(folder / (arguments.name % 0))  # a --name with a folder of its own
    return folder


def animate(arguments) -> int:
    _frame_names(arguments)
    raytracer, bundle, spp = _prepare(arguments, arguments.camera_path)
    frames = _frames(arguments, raytracer)
    folder = _output_dir(arguments)
    options = _cluster_options(arguments)
    farm.connect(options.address)
    try:
        slots = farm.worker_slots(options)
        tasks_per_frame = arguments.tasks_per_frame or math.ceil(default_tasks(slots) / len(frames))
        parts = plan_animation(frames, spp, tasks_per_frame)
        waiting = Counter(part.frame for part in parts)
        with tempfile.TemporaryDirectory(prefix="rtfarm-") as work:
            mergers = {
                frame: ImageMerger(raytracer, Path(work), f"frame{frame}") for frame in waiting
            }

            def add(part: Part, result: PartResult) -> None:
                merger = mergers[part.frame]
                merger.add(result.exr)
                waiting[part.frame] -= 1
                if waiting[part.frame] == 0:
                    merger.write(
                        folder / (arguments.name % part.frame),
                        arguments.scene,
                        arguments.conventions,
                    )
                    merger.discard()

            _run(bundle, arguments, spp, options, parts, add)
    finally:
        farm.disconnect()
    return 0

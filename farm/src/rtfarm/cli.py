"""rtfarm render | animate: the command line.

  rtfarm render SCENE OUT [--spp N] [--tasks K] [--tiles T] [--address ADDR]
                [--gpus-per-task G] [--raytracer PATH] [raytracer options]
  rtfarm animate SCENE CAMERA_PATH OUTDIR [--frames FROM:TO] [--name PATTERN] ...

Bad input is reported as the raytracer does: one `error: ` line on stderr,
exit status 2 for usage and 1 for everything else, and no output file.
"""

from __future__ import annotations

import argparse
import re
import sys

from rtfarm.errors import FarmError

MAX_IMAGE_SIDE = 16384
MAX_SAMPLES = 1 << 20
MAX_LIGHT_SAMPLES = 4096  # src/scene/Limits.hpp kMaxLightSamples
MAX_LIGHT_SPLIT = 64  # src/scene/Limits.hpp kMaxLightSplit
MAX_BOUNCES = 64  # src/scene/Limits.hpp kMaxBounces


class _Parser(argparse.ArgumentParser):
    """argparse with the raytracer's one-line usage errors (status 2)."""

    def error(self, message: str):
        sys.stderr.write(f"error: {message} (see {self.prog} --help)\n")
        raise SystemExit(2)


def _count(low: int, high: int):
    def parse(text: str) -> int:
        if not re.fullmatch(r"\d{1,9}", text) or not low <= int(text) <= high:
            raise argparse.ArgumentTypeError(f"expected a whole number {low}..{high}, got '{text}'")
        return int(text)

    return parse


def _non_negative(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = -1.0
    if not value >= 0 or value == float("inf"):
        raise argparse.ArgumentTypeError(f"expected a non-negative number, got '{text}'")
    return value


def _positive(text: str) -> float:
    value = _non_negative(text)
    if value == 0:
        raise argparse.ArgumentTypeError(f"expected a positive number, got '{text}'")
    return value


def _size(text: str) -> tuple[int, int]:
    match = re.fullmatch(r"(\d{1,9})x(\d{1,9})", text)
    sides = (int(match.group(1)), int(match.group(2))) if match else (0, 0)
    if not all(1 <= side <= MAX_IMAGE_SIDE for side in sides):
        raise argparse.ArgumentTypeError(
            f"expected WIDTHxHEIGHT, each 1..{MAX_IMAGE_SIDE}, got '{text}'"
        )
    return sides


def _frame_range(text: str) -> tuple[int, int]:
    match = re.fullmatch(r"(\d{1,9}):(\d{1,9})", text)
    if not match or int(match.group(1)) >= int(match.group(2)):
        raise argparse.ArgumentTypeError(
            f"expected FROM:TO with FROM < TO, e.g. 0:24, got '{text}'"
        )
    return int(match.group(1)), int(match.group(2))


def _add_render_options(parser: argparse.ArgumentParser) -> None:
    """What the farm passes on to every raytracer (see `raytracer --help`)."""
    group = parser.add_argument_group("render (as raytracer)")
    group.add_argument(
        "--spp",
        type=_count(1, MAX_SAMPLES),
        help="samples per pixel (default: the scene's spp/nsamples/samples, else 16)",
    )
    group.add_argument("--size", type=_size, help="image size WIDTHxHEIGHT (default: the scene's)")
    group.add_argument("--seed", type=_count(0, 2**32 - 1), help="random seed")
    group.add_argument("--sampler", choices=["random", "jittered", "sobol"])
    group.add_argument("--shading", choices=["coursework", "standard"])
    group.add_argument(
        "--conventions", choices=["coursework-a", "coursework-b", "textbook", "physical"]
    )
    group.add_argument(
        "--mode", choices=["binary", "phong", "pathtracer"], help="render mode (the scene's)"
    )
    group.add_argument(
        "--bounces", type=_count(0, MAX_BOUNCES), help="ray depth (the scene's nbounces)"
    )
    group.add_argument("--exposure", type=_positive, help="extra linear exposure")
    group.add_argument("--clamp-indirect", type=_non_negative, help="firefly clamp (biased)")
    group.add_argument(
        "--light-samples",
        type=_count(1, MAX_LIGHT_SAMPLES),
        help="shadow rays per area light and hit, for every area light",
    )
    group.add_argument(
        "--light-split",
        type=_count(1, MAX_LIGHT_SPLIT),
        help="replicas of each hit's area-light estimate (less noise, the same image)",
    )
    group.add_argument("--accel", choices=["bvh", "none"])


def _add_cluster_options(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group("cluster")
    group.add_argument(
        "--address",
        help="Ray cluster (default: $RAY_ADDRESS, the cluster this machine joined "
        "with `ray start`, else a local Ray for this render)",
    )
    group.add_argument(
        "--gpus-per-task",
        type=_non_negative,
        help="GPUs each task asks Ray for (default: 1 where the cluster has GPUs, "
        "else 0: CPU Vulkan such as lavapipe)",
    )
    group.add_argument(
        "--cpus-per-task",
        type=_positive,
        default=1.0,
        help="CPUs each task asks for when it asks for no GPU (default 1)",
    )
    group.add_argument(
        "--max-retries",
        type=_count(0, 100),
        default=3,
        help="times a task whose worker or node died runs again (default 3)",
    )
    group.add_argument(
        "--raytracer",
        help="the raytracer binary, the same path on every node (default: "
        "$RTFARM_RAYTRACER, else the build/raytracer of the checkout rtfarm "
        "is installed from, else raytracer on PATH)",
    )
    group.add_argument("-q", "--quiet", action="store_true", help="no progress line")


def parser() -> argparse.ArgumentParser:
    main = _Parser(prog="rtfarm", description="Renders raytracer scenes on a Ray cluster.")
    commands = main.add_subparsers(dest="command", required=True, parser_class=_Parser)
    render = commands.add_parser("render", help="one image, split into sample ranges and tiles")
    render.add_argument("scene", help="scene file (.json, .gltf, .glb)")
    render.add_argument("output", help="image: .png, .jpg, .ppm, .exr or .hdr")
    render.add_argument(
        "--tasks",
        type=_count(1, 100000),
        help="parts to split the image into (default: 3 per worker slot)",
    )
    render.add_argument(
        "--tiles",
        type=_count(1, MAX_IMAGE_SIDE),
        help="bands of rows per sample range (default: 1, or as many as --tasks "
        "needs beyond the sample count)",
    )
    render.add_argument(
        "--preview",
        help="preview image, rewritten as parts arrive and removed at the end "
        "(default: OUT's name with .preview.png)",
    )
    render.add_argument("--no-preview", action="store_true", help="write no preview")
    render.add_argument(
        "--preview-every",
        type=_positive,
        default=2.0,
        help="seconds between preview updates (default 2)",
    )
    _add_render_options(render)
    _add_cluster_options(render)

    animate = commands.add_parser("animate", help="the frames of a viewer camera path")
    animate.add_argument("scene", help="scene file")
    animate.add_argument("camera_path", help="camera path (the viewer's --camera-path format)")
    animate.add_argument("output_dir", help="folder for the frames (made if missing)")
    animate.add_argument(
        "--frames", type=_frame_range, help="frames FROM:TO (TO excluded; default: all of the path)"
    )
    animate.add_argument(
        "--name",
        default="frame-%04d.png",
        help="frame file names, %%d the frame number; the extension picks the "
        "format (default frame-%%04d.png)",
    )
    animate.add_argument(
        "--tasks-per-frame",
        type=_count(1, MAX_SAMPLES),
        help="sample ranges per frame (default: 1, or more when the cluster "
        "has more slots than there are frames)",
    )
    _add_render_options(animate)
    _add_cluster_options(animate)
    return main


def main(argv: list[str] | None = None) -> int:
    arguments = parser().parse_args(argv)
    from rtfarm import commands

    try:
        if arguments.command == "render":
            return commands.render(arguments)
        return commands.animate(arguments)
    except FarmError as error:
        sys.stderr.write(f"error: {error}\n")
        return 1
    except KeyboardInterrupt:
        sys.stderr.write("\nerror: interrupted\n")
        return 130

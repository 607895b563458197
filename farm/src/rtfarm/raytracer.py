"""Finding and running the `raytracer` binary of the machine this runs on.

The driver uses it to count camera-path frames and to merge parts; every
worker uses its own to render them.
"""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

from rtfarm.errors import FarmError

# farm/src/rtfarm/raytracer.py -> the checkout, whose build/ holds the binary.
_CHECKOUT = Path(__file__).resolve().parents[3]


def find_raytracer(explicit: str | None = None) -> str:
    """The binary to run here: `explicit` (--raytracer), else $RTFARM_RAYTRACER,
    else the build/raytracer of the checkout rtfarm is installed from, else
    `raytracer` on PATH. Raises FarmError when none is there."""
    candidates = [explicit] if explicit else [os.environ.get("RTFARM_RAYTRACER")]
    if not explicit:
        candidates += [str(_CHECKOUT / "build" / "raytracer"), "raytracer"]
    for candidate in filter(None, candidates):
        found = shutil.which(candidate)
        if found:
            return os.path.abspath(found)
    wanted = explicit or os.environ.get("RTFARM_RAYTRACER") or "raytracer"
    raise FarmError(
        f"{wanted}: raytracer binary not found on {os.uname().nodename} "
        "(build it with scripts/build.sh, or give --raytracer PATH)"
    )


def last_error_line(stderr: str) -> str:
    """The raytracer's one-line error (its last `error: ` line), without the prefix."""
    lines = [line for line in stderr.splitlines() if line.strip()]
    errors = [line for line in lines if line.startswith("error: ")]
    if errors:
        return errors[-1][len("error: ") :]
    return lines[-1] if lines else "no message"


def run_checked(command: list[str]) -> str:
    """Runs a local raytracer command; its stdout, or FarmError with its error line."""
    try:
        done = subprocess.run(command, capture_output=True, text=True, check=False)
    except OSError as error:
        raise FarmError(f"{command[0]}: cannot run: {error.strerror}") from error
    if done.returncode != 0:
        raise FarmError(last_error_line(done.stderr))
    return done.stdout


def frame_count(raytracer: str, camera_path: str) -> int:
    """How many frames a viewer camera path lasts (raytracer --frame-count)."""
    output = run_checked([raytracer, "--camera-path", camera_path, "--frame-count"])
    return int(output.strip())


def merge(
    raytracer: str,
    parts: list[Path],
    output: Path,
    scene: str | None = None,
    conventions: str | None = None,
) -> None:
    """`raytracer merge`: the parts' samples into one image, written atomically.
    With `scene`, 8-bit outputs follow that scene's conventions, as its render's."""
    command = [raytracer, "merge", *map(str, parts), str(output)]
    if scene:
        command += ["--scene", scene]
    if conventions:
        command += ["--conventions", conventions]
    run_checked(command)

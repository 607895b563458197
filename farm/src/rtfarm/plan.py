"""Splitting a render into the parts the workers render.

A part is a range of sample indices (`--samples FROM:TO` of the render's
`--spp`), on the whole image or on a tile (a band of rows, `--region`),
of a still or of one frame of a camera path. Merged, a frame's parts give
exactly the image one render of all its samples gives. Samples are split
first; tiles only when a render has fewer samples than tasks, so that one
image can still be spread over more workers than it has samples.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from rtfarm.errors import FarmError

# Tasks per worker slot by default: enough that a slow worker does not hold
# the render up at the end, few enough that the start-up of each raytracer
# (0.3-0.5 s on lavapipe) stays small against its render.
TASKS_PER_SLOT = 3


@dataclass(frozen=True)
class Part:
    index: int  # position in the plan, also the progress board's key
    first_sample: int
    end_sample: int
    region: tuple[int, int, int, int] | None = None  # x, y, width, height of a tile
    frame: int | None = None  # camera-path frame; None for a still
    pixel_share: float = 1.0  # the tile's share of the image's pixels

    @property
    def samples(self) -> int:
        return self.end_sample - self.first_sample

    @property
    def work(self) -> float:
        """Samples per pixel of the whole image this part is worth (progress, ETA)."""
        return self.samples * self.pixel_share

    def raytracer_args(self) -> list[str]:
        args = ["--samples", f"{self.first_sample}:{self.end_sample}"]
        if self.region:
            args += ["--region", ",".join(map(str, self.region))]
        if self.frame is not None:
            args += ["--frame", str(self.frame)]
        return args

    def describe(self) -> str:
        where = f"frame {self.frame} " if self.frame is not None else ""
        tile = (
            f" rows {self.region[1]}..{self.region[1] + self.region[3] - 1}" if self.region else ""
        )
        return f"part {self.index} ({where}samples {self.first_sample}:{self.end_sample}{tile})"


def split_evenly(total: int, pieces: int) -> list[tuple[int, int]]:
    """[0, total) in `pieces` contiguous ranges whose sizes differ by at most one."""
    bounds = [total * i // pieces for i in range(pieces + 1)]
    return [(bounds[i], bounds[i + 1]) for i in range(pieces)]


def default_tasks(slots: int) -> int:
    return TASKS_PER_SLOT * max(slots, 1)


def tiles_for(tasks: int, spp: int) -> int:
    """Tiles a still needs so that `tasks` parts exist although it has only `spp` samples."""
    return 1 if tasks <= spp else math.ceil(tasks / spp)


def plan_still(
    spp: int, tasks: int, tiles: int, width: int | None, height: int | None
) -> list[Part]:
    """Sample ranges (outer) times tiles (inner): the first ranges of every
    tile come first, so a preview covering every pixel comes early."""
    if tiles > 1 and not (width and height):
        raise FarmError("tiles need the image size: give --size WxH")
    if height is not None and tiles > height:
        raise FarmError(f"--tiles {tiles}: the image has only {height} rows")
    ranges = min(spp, max(1, math.ceil(tasks / tiles)))
    bands = split_evenly(height, tiles) if tiles > 1 else [None]
    parts = []
    for first, end in split_evenly(spp, ranges):
        for band in bands:
            region = (0, band[0], width, band[1] - band[0]) if band else None
            share = (band[1] - band[0]) / height if band else 1.0
            parts.append(Part(len(parts), first, end, region, pixel_share=share))
    return parts


def plan_animation(frames: list[int], spp: int, tasks_per_frame: int) -> list[Part]:
    """Each frame in sample ranges, frame by frame, so frames finish in order."""
    ranges = split_evenly(spp, min(spp, max(1, tasks_per_frame)))
    parts = []
    for frame in frames:
        for first, end in ranges:
            parts.append(Part(len(parts), first, end, frame=frame))
    return parts

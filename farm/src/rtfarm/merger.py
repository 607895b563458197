"""Merging an image's parts on the driver as they arrive (`raytracer merge`).

Parts are merged FAN_IN at a time into one file, and those FAN_IN at a
time again, like the digits of a counter: at most FAN_IN - 1 files wait at
each level, the merge holds at most FAN_IN images in memory, and a sample
goes through one merge per level (log_8 of the part count), each adding no
more than a float32 rounding of the mean. Merging each part into one
running image would round once per part; merging all at the end would hold
every part in memory at once.
"""

from __future__ import annotations

import os
from pathlib import Path

from rtfarm import raytracer as rt

FAN_IN = 8
EIGHT_BIT_FORMATS = (".png", ".jpg", ".jpeg", ".ppm")


class ImageMerger:
    def __init__(self, raytracer: str, folder: Path, name: str):
        self.raytracer = raytracer
        self.folder = folder
        self.name = name
        self.levels: list[list[Path]] = [[]]
        self.files_made = 0

    def add(self, exr: bytes) -> None:
        path = self._new_file(0)
        path.write_bytes(exr)
        self.levels[0].append(path)
        self._carry()

    def files(self) -> list[Path]:
        return [path for level in self.levels for path in level]

    def write(self, output: Path, scene: str | None = None, conventions: str | None = None) -> None:
        """The merged image, written atomically by the raytracer. 8-bit formats
        follow `scene`'s conventions (as its own render writes them)."""
        eight_bit = output.suffix.lower() in EIGHT_BIT_FORMATS
        rt.merge(
            self.raytracer,
            self.files(),
            output,
            scene if eight_bit else None,
            conventions if eight_bit else None,
        )

    def discard(self) -> None:
        for path in self.files():
            path.unlink(missing_ok=True)
        self.levels = [[]]

    def _new_file(self, level: int) -> Path:
        self.files_made += 1
        return self.folder / f"{self.name}-level{level}-{self.files_made}.exr"

    def _carry(self) -> None:
        level = 0
        while len(self.levels[level]) == FAN_IN:
            merged = self._new_file(level + 1)
            rt.merge(self.raytracer, self.levels[level], merged)
            for path in self.levels[level]:
                os.unlink(path)
            self.levels[level] = []
            if len(self.levels) == level + 1:
                self.levels.append([])
            self.levels[level + 1].append(merged)
            level += 1

"""The one progress line of a whole cluster's render.

`rtfarm: 7/16 tasks, 2 running, 1.85 Msamples/s, ETA 12 s`: parts merged
of all, parts whose raytracer is rendering now, pixel-samples per second
of wall time of all workers together (their rates summed), and the time
left at that rate. Running parts count with the share their raytracer has
reported (to a ProgressBoard actor), so long parts move the line too.
"""

from __future__ import annotations

import sys
import time

from rtfarm.plan import Part

# Without a terminal, a line this often at most (logs stay short).
_LOG_INTERVAL_SECONDS = 10.0


class ProgressBoard:
    """A Ray actor: the latest fraction each running part's raytracer reported."""

    def __init__(self):
        self._fractions: dict[int, float] = {}

    def report(self, part_index: int, fraction: float) -> None:
        self._fractions[part_index] = fraction

    def snapshot(self) -> dict[int, float]:
        return dict(self._fractions)


def _duration(seconds: float) -> str:
    if seconds < 100:
        return f"{seconds:.0f} s"
    if seconds < 6000:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"


class ProgressLine:
    def __init__(self, parts: list[Part], enabled: bool = True, stream=sys.stderr):
        self.total = len(parts)
        self.total_work = sum(part.work for part in parts) or 1.0
        self.work = {part.index: part.work for part in parts}
        self.enabled = enabled
        self.stream = stream
        self.interactive = stream.isatty()
        self.start = time.monotonic()
        self.last_written = 0.0
        self.done_work = 0.0
        self.done_tasks = 0
        self.pixel_samples = 0.0
        self.pixel_samples_per_work = 0.0  # learned from finished parts
        self.line_open = False  # a terminal line without its newline yet

    def part_done(self, part: Part, pixel_samples: float) -> None:
        self.done_tasks += 1
        self.done_work += part.work
        self.pixel_samples += pixel_samples
        self.pixel_samples_per_work = self.pixel_samples / self.done_work

    def text(self, running: dict[int, float]) -> str:
        elapsed = max(time.monotonic() - self.start, 1e-9)
        in_flight = sum(self.work[index] * fraction for index, fraction in running.items())
        done = min(self.done_work + in_flight, self.total_work)
        rate = (self.pixel_samples + in_flight * self.pixel_samples_per_work) / elapsed
        line = f"rtfarm: {self.done_tasks}/{self.total} tasks, {len(running)} running"
        if rate > 0:
            line += f", {rate * 1e-6:.3g} Msamples/s"
        if self.done_tasks == self.total:
            line += f", done in {_duration(elapsed)}"
        elif done > 0:
            line += f", ETA {_duration(elapsed * (self.total_work - done) / done)}"
        return line

    def show(self, running: dict[int, float], final: bool = False) -> None:
        if not self.enabled:
            return
        now = time.monotonic()
        if not self.interactive and not final and now - self.last_written < _LOG_INTERVAL_SECONDS:
            return
        self.last_written = now
        text = self.text(running)
        if self.interactive:
            self.stream.write("\r" + text + "\x1b[K" + ("\n" if final else ""))
            self.line_open = not final
        else:
            self.stream.write(text + "\n")
        self.stream.flush()

    def close(self) -> None:
        """Ends an unfinished terminal line, so that an error starts a line of its own."""
        if self.line_open:
            self.stream.write("\n")
            self.stream.flush()
            self.line_open = False

"""What the farm costs and gains, on local Ray clusters of this machine
(bench/run-farm.sh; a benchmark, not a test).

1. Overhead per task, on a cluster of one worker: each part's span on the
   worker minus its raytracer's own run (the part's folder, the EXR read),
   plus the worker's idle gap before the next part (Ray's scheduling, the
   bundle handed over, the result put in the object store). The
   raytracer's run is what a plain `raytracer --samples FROM:TO` of the
   part costs, start-up included. Also the whole `rtfarm render` command
   against plain runs of the same parts plus `raytracer merge`: the fixed
   cost (Python, Ray connection, shutdown).
2. Speed-up from one worker to two (a second node joins), with lavapipe's
   default thread count and with one thread per raytracer
   (LP_NUM_THREADS=1): the whole command, and the span of its tasks (first
   start to last end), which leaves the fixed cost out.

Times are the best of --repeats runs; another process on the machine
slows some runs, and the best is the least disturbed.
"""

from __future__ import annotations

import argparse
import os
import secrets
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from rtfarm import farm
from rtfarm.bundle import make_bundle
from rtfarm.localcluster import LocalCluster
from rtfarm.plan import plan_still, split_evenly
from rtfarm.progress import ProgressLine
from rtfarm.worker import RenderJob

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "scenes" / "default.json"


def timed(command: list[str], env: dict[str, str] | None = None) -> float:
    start = time.monotonic()
    subprocess.run(
        command, check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
    )
    return time.monotonic() - start


class Bench:
    def __init__(self, raytracer: str, repeats: int, folder: Path):
        self.raytracer = raytracer
        self.repeats = repeats
        self.folder = folder
        self.token = secrets.token_hex(32)  # this process drives every cluster

    def cluster(self, nodes: int, env: dict[str, str] | None = None) -> LocalCluster:
        env = {"RTFARM_RAYTRACER": self.raytracer, **(env or {})}
        return LocalCluster(nodes=nodes, cpus_per_node=1, env=env, token=self.token)

    def best(self, run) -> float:
        return min(run() for _ in range(self.repeats))

    def plain(self, size: str, spp: int, parts: int = 1, env=None) -> float:
        """The render as `parts` raytracer runs one after the other (merged when more than one)."""

        def run() -> float:
            files = [self.folder / f"part{i}.exr" for i in range(parts)]
            seconds = 0.0
            for (first, end), part in zip(split_evenly(spp, parts), files):
                seconds += timed(
                    [self.raytracer, str(SCENE), str(part), "--size", size, "--spp", str(spp)]
                    + ["--samples", f"{first}:{end}", "-q"],
                    env,
                )
            if parts > 1:
                merge = [self.raytracer, "merge", *map(str, files), str(self.folder / "m.exr")]
                seconds += timed(merge, env)
            return seconds

        return self.best(run)

    def command(self, cluster: LocalCluster, size: str, spp: int, tasks: int) -> float:
        """The whole `rtfarm render`, as a user runs it."""
        command = [sys.executable, "-m", "rtfarm", "render", str(SCENE)]
        command += [str(self.folder / "farm.exr"), "--size", size, "--spp", str(spp)]
        command += ["--tasks", str(tasks), "--no-preview", "-q", "--address", cluster.address]
        return self.best(
            lambda: timed(command + ["--raytracer", self.raytracer], cluster.client_env)
        )

    def task_results(self, cluster: LocalCluster, size: str, spp: int, tasks: int) -> list:
        """One render's PartResults (spans on the worker's clock), driven from here."""
        width, height = map(int, size.split("x"))
        parts = plan_still(spp, tasks, 1, width, height)
        job = RenderJob(self.raytracer, ["--spp", str(spp), "--size", size])
        results = []
        os.environ.update(cluster.auth)
        farm.connect(cluster.address)
        try:
            runner = farm.PartRunner(
                make_bundle(str(SCENE)),
                job,
                farm.ClusterOptions(cluster.address),
                ProgressLine(parts, enabled=False),
            )
            runner.run(parts, lambda part, result: results.append(result))
        finally:
            farm.disconnect()
        return sorted(results, key=lambda result: result.started)

    def span(self, cluster: LocalCluster, size: str, spp: int, tasks: int) -> float:
        def run() -> float:
            results = self.task_results(cluster, size, spp, tasks)
            return results[-1].finished - results[0].started

        return self.best(run)


def overhead(bench: Bench, cluster: LocalCluster, size: str, spp_per_task: int, tasks: int):
    """Per-task costs (seconds) on one worker, from the run with the least of them."""
    best = None
    for _ in range(bench.repeats):
        results = bench.task_results(cluster, size, spp_per_task * tasks, tasks)
        inside = [r.finished - r.started - r.seconds for r in results]
        gaps = [later.started - earlier.finished for earlier, later in zip(results, results[1:])]
        raytracer = statistics.mean(r.seconds for r in results)
        row = (statistics.mean(inside), statistics.mean(gaps), raytracer)
        if best is None or row[0] + row[1] < best[0] + best[1]:
            best = row
    return best


def speedup(bench: Bench, env: dict[str, str], size: str, spp: int, tasks: int):
    plain = bench.plain(size, spp, env={**os.environ, **env})
    with bench.cluster(1, env) as cluster:
        bench.command(cluster, size, 2, 2)  # starts the worker, fills the shader caches
        one = (bench.command(cluster, size, spp, tasks), bench.span(cluster, size, spp, tasks))
        cluster.add_node()
        cluster.wait_for_nodes(2)
        bench.command(cluster, size, 2, 2)
        two = (bench.command(cluster, size, spp, tasks), bench.span(cluster, size, spp, tasks))
    return plain, one, two


def print_overhead(costs, whole, size: str, spp_per_task: int, tasks: int) -> None:
    inside, gap, raytracer = costs
    plain_parts, command = whole
    print(
        f"\nOverhead on one worker (default scene {size}, {tasks} tasks of {spp_per_task} spp):\n"
    )
    print("| per task | seconds |")
    print("|---|---|")
    print(f"| the raytracer's own run (= a plain render of the part) | {raytracer:.3f} |")
    print(f"| in the task around it (part folder, EXR read) | {inside:.3f} |")
    print(f"| worker idle before the next task (scheduling, bundle, result) | {gap:.3f} |")
    print(f"| farm overhead per task | {inside + gap:.3f} |")
    print(f"\n| {tasks} tasks | seconds |")
    print("|---|---|")
    print(f"| plain: the parts one after the other, then raytracer merge | {plain_parts:.2f} |")
    print(f"| rtfarm render (Python, Ray connection, tasks, merges, shutdown) | {command:.2f} |")
    fixed = command - tasks * (raytracer + inside + gap)
    print(f"| fixed cost of one rtfarm command (the rest) | {fixed:.2f} |")


def print_speedup(rows, size: str, spp: int, tasks: int) -> None:
    print(f"\nOne worker vs two (default scene {size}, {spp} spp, {tasks} tasks, 1 CPU a node):\n")
    print(
        "| lavapipe threads | plain render | rtfarm, 1 worker | 2 workers | speed-up "
        "| task span, 1 worker | 2 workers | speed-up |"
    )
    print("|---|---|---|---|---|---|---|---|")
    for label, (plain, one, two) in rows:
        print(
            f"| {label} | {plain:.2f} s | {one[0]:.2f} s | {two[0]:.2f} s | {one[0] / two[0]:.2f}x "
            f"| {one[1]:.2f} s | {two[1]:.2f} s | {one[1] / two[1]:.2f}x |"
        )


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--raytracer", default=str(ROOT / "build" / "raytracer"))
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--size", default="160x120", help="image size of the overhead renders")
    parser.add_argument("--spp-per-task", type=int, default=4)
    parser.add_argument("--tasks", type=int, default=8)
    parser.add_argument("--speedup-size", default="320x240", help="image size, speed-up render")
    parser.add_argument("--spp", type=int, default=64, help="samples of the speed-up render")
    arguments = parser.parse_args()
    cores = os.cpu_count()
    print(
        f"rtfarm benchmark: {cores} CPU cores, load average {os.getloadavg()[0]:.2f} at the start"
    )
    with tempfile.TemporaryDirectory(prefix="rtfarm-bench-") as folder:
        bench = Bench(arguments.raytracer, arguments.repeats, Path(folder))
        size, spp, tasks = arguments.size, arguments.spp_per_task * arguments.tasks, arguments.tasks
        with bench.cluster(1) as cluster:
            bench.command(cluster, size, 2, 2)  # starts the worker, fills the shader caches
            costs = overhead(bench, cluster, size, arguments.spp_per_task, tasks)
            whole = (bench.plain(size, spp, tasks), bench.command(cluster, size, spp, tasks))
        print_overhead(costs, whole, size, arguments.spp_per_task, tasks)
        size, spp = arguments.speedup_size, arguments.spp
        rows = [(f"default ({cores})", speedup(bench, {}, size, spp, tasks))]
        rows.append(("1 per raytracer", speedup(bench, {"LP_NUM_THREADS": "1"}, size, spp, tasks)))
        print_speedup(rows, size, spp, tasks)
    print(f"\nload average {os.getloadavg()[0]:.2f} at the end")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""What the farm costs and gains, on local Ray clusters of this machine
(bench/run-farm.sh; a benchmark, not a test).

1. Overhead: the render split in K parts, run as K plain raytracer
   commands plus one merge, against `rtfarm render --tasks K` on a cluster
   of one worker; fitted over two K to a fixed cost (Python, Ray
   connection, the bundle, the final merge) and a cost per task
   (scheduling, the part's folder, its EXR through the object store, the
   driver's merges).
2. Speed-up: one render on one worker, then on two (a second node joins),
   with lavapipe's default thread count and with one thread per raytracer
   (LP_NUM_THREADS=1), against a plain render of the whole image.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from rtfarm.localcluster import LocalCluster
from rtfarm.plan import split_evenly

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "scenes" / "default.json"


def timed(command: list[str], env: dict[str, str] | None = None) -> float:
    start = time.monotonic()
    subprocess.run(
        command, check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
    )
    return time.monotonic() - start


def best(repeats: int, run) -> float:
    return min(run() for _ in range(repeats))


class Bench:
    def __init__(self, raytracer: str, size: str, repeats: int, folder: Path):
        self.raytracer = raytracer
        self.size = size
        self.repeats = repeats
        self.folder = folder

    def plain_parts(self, spp: int, parts: int, env=None) -> float:
        """The render as `parts` raytracer commands one after the other, then merged."""

        def run() -> float:
            files = [self.folder / f"part{i}.exr" for i in range(parts)]
            seconds = 0.0
            for (first, end), part in zip(split_evenly(spp, parts), files):
                seconds += timed(
                    [
                        self.raytracer,
                        str(SCENE),
                        str(part),
                        "--size",
                        self.size,
                        "--spp",
                        str(spp),
                        "--samples",
                        f"{first}:{end}",
                        "-q",
                    ],
                    env,
                )
            return seconds + timed(
                [self.raytracer, "merge", *map(str, files), str(self.folder / "merged.exr")], env
            )

        return best(self.repeats, run)

    def farm(self, cluster: LocalCluster, spp: int, tasks: int) -> float:
        command = [
            sys.executable,
            "-m",
            "rtfarm",
            "render",
            str(SCENE),
            str(self.folder / "farm.exr"),
            "--size",
            self.size,
            "--spp",
            str(spp),
            "--tasks",
            str(tasks),
            "--no-preview",
            "-q",
            "--address",
            cluster.address,
            "--raytracer",
            self.raytracer,
        ]
        return best(self.repeats, lambda: timed(command, cluster.client_env))

    def overhead(self, cluster: LocalCluster, spp_per_task: int, counts=(2, 8)) -> list[tuple]:
        rows = []
        for tasks in counts:
            spp = spp_per_task * tasks
            rows.append((tasks, self.plain_parts(spp, tasks), self.farm(cluster, spp, tasks)))
        return rows

    def speedup(self, env: dict[str, str], spp: int, tasks: int, label: str) -> list[tuple]:
        plain = best(
            self.repeats,
            lambda: timed(
                [
                    self.raytracer,
                    str(SCENE),
                    str(self.folder / "plain.exr"),
                    "--size",
                    self.size,
                    "--spp",
                    str(spp),
                    "-q",
                ],
                {**os.environ, **env},
            ),
        )
        with LocalCluster(
            nodes=1, cpus_per_node=1, env={"RTFARM_RAYTRACER": self.raytracer, **env}
        ) as cluster:
            self.farm(cluster, 2, 2)  # starts the worker, fills the shader caches
            one = self.farm(cluster, spp, tasks)
            cluster.add_node()
            cluster.wait_for_nodes(2)
            self.farm(cluster, 2, 2)
            two = self.farm(cluster, spp, tasks)
        return [(label, plain, one, two)]


def print_overhead(rows: list[tuple], spp_per_task: int, size: str) -> None:
    (k1, plain1, farm1), (k2, plain2, farm2) = rows[0], rows[-1]
    per_task = ((farm2 - plain2) - (farm1 - plain1)) / (k2 - k1)
    fixed = (farm1 - plain1) - k1 * per_task
    print(
        f"\nOverhead on one worker (default scene {size}, {spp_per_task} spp per task, best of runs):\n"
    )
    print("| tasks | plain parts + merge, s | rtfarm render, s | farm - plain, s |")
    print("|---|---|---|---|")
    for tasks, plain, farm in rows:
        print(f"| {tasks} | {plain:.2f} | {farm:.2f} | {farm - plain:.2f} |")
    print(
        f"\nPer task: {per_task:.2f} s; fixed (Python, Ray connection, bundle, shutdown): {fixed:.2f} s"
    )
    plain_task = plain1 / k1
    print(f"(a plain part alone takes {plain_task:.2f} s, start-up included)")


def print_speedup(rows: list[tuple], spp: int, tasks: int, size: str) -> None:
    print(
        f"\nOne worker vs two (default scene {size}, {spp} spp, {tasks} tasks, one CPU per node):\n"
    )
    print(
        "| lavapipe threads | plain render, s | farm, 1 worker, s | farm, 2 workers, s | speed-up |"
    )
    print("|---|---|---|---|---|")
    for label, plain, one, two in rows:
        print(f"| {label} | {plain:.2f} | {one:.2f} | {two:.2f} | {one / two:.2f}x |")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--raytracer", default=str(ROOT / "build" / "raytracer"))
    parser.add_argument("--size", default="160x120", help="image size of the overhead renders")
    parser.add_argument(
        "--speedup-size", default="320x240", help="image size of the speed-up render"
    )
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--spp-per-task", type=int, default=4)
    parser.add_argument("--spp", type=int, default=64, help="samples of the speed-up render")
    parser.add_argument("--tasks", type=int, default=8, help="tasks of the speed-up render")
    arguments = parser.parse_args()
    cores = os.cpu_count()
    print(
        f"rtfarm benchmark: {cores} CPU cores, load average {os.getloadavg()[0]:.2f} at the start"
    )
    with tempfile.TemporaryDirectory(prefix="rtfarm-bench-") as folder:
        bench = Bench(arguments.raytracer, arguments.size, arguments.repeats, Path(folder))
        with LocalCluster(
            nodes=1, cpus_per_node=1, env={"RTFARM_RAYTRACER": arguments.raytracer}
        ) as cluster:
            bench.farm(cluster, 2, 2)  # starts the worker, fills the shader caches
            overhead = bench.overhead(cluster, arguments.spp_per_task)
        print_overhead(overhead, arguments.spp_per_task, arguments.size)
        bench.size = arguments.speedup_size
        rows = bench.speedup({}, arguments.spp, arguments.tasks, f"default ({cores})")
        rows += bench.speedup(
            {"LP_NUM_THREADS": "1"}, arguments.spp, arguments.tasks, "1 per raytracer"
        )
        print_speedup(rows, arguments.spp, arguments.tasks, arguments.speedup_size)
    print(f"\nload average {os.getloadavg()[0]:.2f} at the end")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

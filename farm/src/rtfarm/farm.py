"""The driver's side of Ray: connecting, and running parts on the cluster.

Every part is one Ray task that asks for `gpus_per_task` GPUs (or, on
machines without one, `cpus_per_task` CPUs: a CPU Vulkan device such as
lavapipe). Ray retries a task whose worker or node died, or whose
raytracer was killed, up to `max_retries` times, on any node; a part the
raytracer itself refuses (a broken scene) ends the whole render at once
with the raytracer's one-line error, the other tasks cancelled.
"""

from __future__ import annotations

import contextlib
import logging
import os
import socket
import sys
import tempfile
import time
from dataclasses import dataclass
from typing import Callable

from rtfarm.bundle import Bundle
from rtfarm.errors import FarmError
from rtfarm.plan import Part
from rtfarm.progress import ProgressBoard, ProgressLine
from rtfarm.worker import PartResult, RaytracerCrashed, RenderFailed, RenderJob, render_part

_WAIT_SECONDS = 0.5  # how often the loop looks at progress without a result
_BOARD_INTERVAL_SECONDS = 1.0
_CONNECT_SECONDS = 10.0


@dataclass(frozen=True)
class ClusterOptions:
    address: str | None = None  # None: $RAY_ADDRESS, a cluster on this machine, or a new local one
    gpus_per_task: float | None = None  # None: 1 where the cluster has GPUs, else 0
    cpus_per_task: float = 1.0  # with 0 GPUs per task
    max_retries: int = 3


def _check_reachable(address: str) -> None:
    """A head at HOST:PORT that does not answer fails now: Ray itself would
    keep trying to reach it for minutes."""
    host, _, port = address.rpartition(":")
    if "://" in address or not port.isdigit():
        return  # ray://, auto, ...: Ray's own forms
    try:
        socket.create_connection((host or "127.0.0.1", int(port)), timeout=_CONNECT_SECONDS).close()
    except OSError as error:
        reason = error.strerror or str(error) or type(error).__name__
        raise FarmError(f"cannot connect to the Ray cluster {address}: {reason}") from None


def connect(address: str | None) -> None:
    """Joins the Ray cluster at `address`; without one, the cluster this
    machine belongs to (RAY_ADDRESS, `ray start`), else a new local one."""
    _check_reachable(address or os.environ.get("RAY_ADDRESS", ""))
    with _stderr_kept() as ray_messages:
        try:
            _init(address)
            return
        except (ConnectionError, RuntimeError, ValueError) as error:
            failure = error
    where = f" {address}" if address else ""
    if "InvalidAuthToken" in ray_messages.text:
        raise FarmError(
            f"the Ray cluster{where} refused this machine's token: set RAY_AUTH_MODE=token "
            "and the cluster's token (~/.ray/auth_token or RAY_AUTH_TOKEN)"
        )
    raise FarmError(f"cannot connect to the Ray cluster{where}: {_one_line(failure)}")


def _init(address: str | None) -> None:
    import ray

    quiet = {"logging_level": logging.ERROR, "log_to_driver": False}
    if address or os.environ.get("RAY_ADDRESS"):
        ray.init(address=address, **quiet)
        return
    try:
        ray.init(address="auto", **quiet)
    except ConnectionError:
        ray.init(include_dashboard=False, **quiet)


class _stderr_kept(contextlib.AbstractContextManager):
    """Keeps what Ray's C++ core writes to stderr while it connects (a line
    per failed attempt) out of the user's terminal, for the error to read."""

    def __enter__(self):
        sys.stderr.flush()
        self.file = tempfile.TemporaryFile(mode="w+")
        self.saved = os.dup(2)
        os.dup2(self.file.fileno(), 2)
        self.text = ""
        return self

    def __exit__(self, *exc):
        sys.stderr.flush()
        os.dup2(self.saved, 2)
        os.close(self.saved)
        self.file.seek(0)
        self.text = self.file.read()
        self.file.close()
        return False


def disconnect() -> None:
    import ray

    if ray.is_initialized():
        ray.shutdown()


def _resources(options: ClusterOptions) -> dict[str, float]:
    """Ray resources of one task; checks the cluster can ever run it."""
    import ray

    total = ray.cluster_resources()
    gpus = options.gpus_per_task
    if gpus is None:
        gpus = 1.0 if total.get("GPU", 0) >= 1 else 0.0
    if gpus > 0:
        if total.get("GPU", 0) < gpus:
            raise FarmError(
                f"--gpus-per-task {gpus:g}: the cluster has {total.get('GPU', 0):g} GPU(s)"
            )
        return {"num_gpus": gpus, "num_cpus": 0}
    if total.get("CPU", 0) < options.cpus_per_task:
        raise FarmError(
            f"--cpus-per-task {options.cpus_per_task:g}: the cluster has {total.get('CPU', 0):g} CPU(s)"
        )
    return {"num_gpus": 0, "num_cpus": options.cpus_per_task}


def worker_slots(options: ClusterOptions) -> int:
    """How many parts the cluster renders at once."""
    import ray

    resources = _resources(options)
    total = ray.cluster_resources()
    if resources["num_gpus"] > 0:
        return int(total.get("GPU", 0) // resources["num_gpus"])
    return int(total.get("CPU", 0) // resources["num_cpus"])


def _one_line(error: BaseException) -> str:
    text = str(error).strip()
    return text.splitlines()[0] if text else type(error).__name__


class PartRunner:
    """Runs parts on the cluster and hands each result to `on_result` as it arrives."""

    def __init__(
        self, bundle: Bundle, job: RenderJob, options: ClusterOptions, progress: ProgressLine
    ):
        self.bundle = bundle
        self.job = job
        self.options = options
        self.progress = progress
        self.board = None
        self.running: dict[int, float] = {}
        self.board_read_at = 0.0

    def run(self, parts: list[Part], on_result: Callable[[Part, PartResult], None]) -> None:
        import ray

        task = ray.remote(render_part).options(
            **_resources(self.options),
            max_retries=self.options.max_retries,
            retry_exceptions=[RaytracerCrashed],
        )
        self.board = self._start_board()
        bundle_ref = ray.put(self.bundle)  # sent once to each node that needs it
        pending = {task.remote(bundle_ref, self.job, part, self.board): part for part in parts}
        try:
            while pending:
                ready, _ = ray.wait(list(pending), num_returns=1, timeout=_WAIT_SECONDS)
                for ref in ready:
                    part = pending.pop(ref)
                    result = self._result(ref, part)
                    self.running.pop(part.index, None)
                    on_result(part, result)
                    self.progress.part_done(part, result.pixel_samples)
                if pending:  # the caller writes the last line
                    self._read_board(set(pending.values()))
                    self.progress.show(self.running)
        finally:
            for ref in pending:
                ray.cancel(ref, force=True)

    def _start_board(self):
        """The progress actor, on the driver's node (none if it cannot start)."""
        import ray
        from ray.util.scheduling_strategies import NodeAffinitySchedulingStrategy

        try:
            here = ray.get_runtime_context().get_node_id()
            strategy = NodeAffinitySchedulingStrategy(node_id=here, soft=True)
            return (
                ray.remote(ProgressBoard).options(num_cpus=0, scheduling_strategy=strategy).remote()
            )
        except Exception:
            return None

    def _read_board(self, pending: set[Part]) -> None:
        import ray

        now = time.monotonic()
        if self.board is None or now - self.board_read_at < _BOARD_INTERVAL_SECONDS:
            return
        self.board_read_at = now
        try:
            reported = ray.get(self.board.snapshot.remote(), timeout=2.0)
        except Exception:  # a lost board only costs the line its in-flight share
            self.board = None
            return
        waiting = {part.index for part in pending}
        self.running = {index: fraction for index, fraction in reported.items() if index in waiting}

    def _result(self, ref, part: Part) -> PartResult:
        import ray

        attempts = self.options.max_retries + 1
        try:
            return ray.get(ref)
        except ray.exceptions.RayTaskError as error:
            cause = error.cause
            if isinstance(cause, RenderFailed):
                raise FarmError(_one_line(cause)) from None
            if isinstance(cause, RaytracerCrashed):
                raise FarmError(f"{_one_line(cause)} ({attempts} attempts)") from None
            raise FarmError(
                f"{part.describe()}: {type(cause).__name__}: {_one_line(cause)}"
            ) from None
        except ray.exceptions.RayError as error:
            raise FarmError(
                f"{part.describe()}: failed {attempts} times, last: {type(error).__name__}: "
                f"{_one_line(error)}"
            ) from None

"""A Ray cluster of several nodes on this machine's loopback, for the tests
and the benchmark: a head and more nodes, each started by `ray start` with
its own temporary folder and ports, each in a session of its own so that
stopping it ends every process it started (workers included) and nothing
else, however it was left.

  python -m rtfarm.localcluster --nodes 2 -- rtfarm render ... --address {address}

runs a command against a fresh cluster and stops the cluster afterwards.
"""

from __future__ import annotations

import argparse
import os
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

_RAY = str(Path(sys.executable).with_name("ray"))
_STOP_GRACE_SECONDS = 2.0


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


@dataclass
class Node:
    index: int
    folder: Path  # the node's --temp-dir
    session: int  # the session id of every process the node runs

    def processes(self) -> list[int]:
        found = []
        for entry in os.listdir("/proc"):
            if entry.isdigit():
                try:
                    # After the command in parentheses: state ppid pgrp session ...
                    fields = Path(f"/proc/{entry}/stat").read_text().rsplit(")", 1)[1].split()
                except OSError:
                    continue
                if int(fields[3]) == self.session and fields[0] != "Z":  # zombies are gone
                    found.append(int(entry))
        return found

    def signal_all(self, signum: int) -> None:
        for pid in self.processes():
            try:
                os.kill(pid, signum)
            except ProcessLookupError:
                pass


class LocalCluster:
    def __init__(
        self,
        nodes: int = 2,
        cpus_per_node: int = 1,
        env: dict[str, str] | None = None,
        token: str | None = None,
    ):
        # Short: Ray's Unix sockets live below it (108-byte path limit).
        self.root = Path(tempfile.mkdtemp(prefix="rtf-", dir="/tmp"))
        self.node_count = nodes
        self.cpus_per_node = cpus_per_node
        # Ray's token authentication, with a token of this cluster's own: the
        # same whatever ~/.ray/auth_token holds, and no one else's cluster.
        # (A process that drives several clusters in turn needs one token for
        # all: Ray keeps the first it read.)
        token = token or secrets.token_hex(32)
        self.auth = {"RAY_AUTH_MODE": "token", "RAY_AUTH_TOKEN": token}
        self.env = {**os.environ, **(env or {}), **self.auth}
        self.env.pop("RAY_ADDRESS", None)
        # The workers' temporary files go when the cluster does.
        self.env["TMPDIR"] = str(self.root / "tmp")
        self.port = free_port()
        self.address = f"127.0.0.1:{self.port}"
        self.nodes: list[Node] = []

    @property
    def client_env(self) -> dict[str, str]:
        """The environment a driver (rtfarm) needs to join this cluster."""
        client = {**os.environ, **self.auth}
        client.pop("RAY_ADDRESS", None)
        return client

    def __enter__(self) -> "LocalCluster":
        try:
            self.start()
        except BaseException:
            self.stop()
            raise
        return self

    def __exit__(self, *exc) -> None:
        self.stop()

    def start(self) -> None:
        (self.root / "tmp").mkdir()
        for index in range(self.node_count):
            self.add_node()
        self.wait_for_nodes(self.node_count)

    def add_node(self) -> Node:
        index = len(self.nodes)
        folder = self.root / f"node{index}"
        folder.mkdir()
        role = (
            [
                "--head",
                f"--port={self.port}",
                f"--ray-client-server-port={free_port()}",
                "--include-dashboard=false",
            ]
            if index == 0
            else [f"--address={self.address}"]
        )
        command = [
            _RAY,
            "start",
            *role,
            "--node-ip-address=127.0.0.1",
            f"--num-cpus={self.cpus_per_node}",
            "--num-gpus=0",
            f"--temp-dir={folder}",
            f"--dashboard-agent-listen-port={free_port()}",
            f"--metrics-export-port={free_port()}",
            "--disable-usage-stats",
        ]
        log = (self.root / f"node{index}.log").open("w")
        starter = subprocess.Popen(
            command,
            env=self.env,
            stdout=log,
            stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL,
            start_new_session=True,
        )
        node = Node(index, folder, starter.pid)
        self.nodes.append(node)
        if starter.wait() != 0:
            raise RuntimeError(f"ray start failed (node {index}): see {log.name}")
        return node

    def wait_for_nodes(self, count: int, timeout: float = 120.0) -> None:
        """Until the head's GCS lists `count` live nodes."""
        script = (
            "import ray,sys; ray.init(address=sys.argv[1], logging_level='ERROR');"
            "print(sum(n['Alive'] for n in ray.nodes()))"
        )
        deadline = time.monotonic() + timeout
        while True:
            done = subprocess.run(
                [sys.executable, "-c", script, self.address],
                env=self.env,
                capture_output=True,
                text=True,
            )
            if done.returncode == 0 and done.stdout.strip() == str(count):
                return
            if time.monotonic() > deadline:
                raise RuntimeError(
                    f"{count} Ray nodes not up after {timeout:.0f} s: {done.stderr[-500:]}"
                )
            time.sleep(1.0)

    def stop_node(self, node: Node) -> None:
        node.signal_all(signal.SIGTERM)
        deadline = time.monotonic() + _STOP_GRACE_SECONDS
        while node.processes() and time.monotonic() < deadline:
            time.sleep(0.2)
        node.signal_all(signal.SIGKILL)

    def stop(self) -> None:
        for node in reversed(self.nodes):
            self.stop_node(node)
        shutil.rmtree(self.root, ignore_errors=True)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--nodes", type=int, default=2)
    parser.add_argument("--cpus-per-node", type=int, default=1)
    parser.add_argument(
        "command",
        nargs=argparse.REMAINDER,
        help="-- COMMAND...; {address} becomes the cluster's address",
    )
    arguments = parser.parse_args()
    command = arguments.command[1:] if arguments.command[:1] == ["--"] else arguments.command
    with LocalCluster(arguments.nodes, arguments.cpus_per_node) as cluster:
        return subprocess.call(
            [part.replace("{address}", cluster.address) for part in command], env=cluster.client_env
        )


if __name__ == "__main__":
    raise SystemExit(main())

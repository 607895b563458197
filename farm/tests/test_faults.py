"""Faults: a worker or a whole node killed mid-render costs time, not
samples; a part the raytracer refuses ends the render at once."""

import os
import signal
import subprocess
import time
from pathlib import Path

import pytest

from conftest import (
    DEFAULT_SCENE,
    FARM_TIMEOUT_SECONDS,
    RTFARM,
    assert_same_image,
    one_error_line,
    render_single,
    run_farm,
)
from rtfarm.localcluster import LocalCluster

# Parts of a second or more each on one CPU, so that a kill lands mid-part
# (kill_mid_part waits until a part has run for half a second). At 480
# samples a part rendered in 0.31 s on one lavapipe thread (2026-12-05),
# too close to that wait: the test failed when the part was quick.
LONG_SPP = 1920
LONG_RENDER = ["--size", "64x48", "--spp", str(LONG_SPP), "--tasks", "4"]


def raytracers_on(node):
    """(worker pid, raytracer pid) of each part rendering on `node` now."""
    found = []
    for pid in node.processes():
        try:
            command = Path(f"/proc/{pid}/cmdline").read_bytes().split(b"\0")
            parent = int(Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[1])
        except OSError:
            continue
        if command[0].endswith(b"raytracer") and len(command) > 1 and b"rtfarm-part-" in command[1]:
            found.append((parent, pid))
    return found


def ended(pid: int, wait_seconds: float = 5.0) -> bool:
    """Whether process `pid` has ended (within `wait_seconds`). A zombie has
    ended: it waits only for its new parent (here whatever reaps orphans,
    which may be slow or never) to collect its exit status."""
    deadline = time.monotonic() + wait_seconds
    while True:
        try:
            state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
        except OSError:
            return True
        if state in ("Z", "X"):
            return True
        if time.monotonic() >= deadline:
            return False
        time.sleep(0.05)


def kill_mid_part(farm: subprocess.Popen, node, kill) -> tuple[int, int] | None:
    """Once a part has rendered on `node` for a moment, `kill(worker, raytracer)`."""
    first_seen = {}
    deadline = time.monotonic() + FARM_TIMEOUT_SECONDS
    while farm.poll() is None and time.monotonic() < deadline:
        for worker, tracer in raytracers_on(node):
            first_seen.setdefault(tracer, time.monotonic())
            if time.monotonic() - first_seen[tracer] > 0.5:
                kill(worker, tracer)
                return worker, tracer
        time.sleep(0.05)
    return None


def start_long_render(cluster, output):
    return subprocess.Popen(
        [
            *RTFARM,
            "render",
            str(DEFAULT_SCENE),
            str(output),
            *LONG_RENDER,
            "--preview-every",
            "0.2",
            "--address",
            cluster.address,
        ],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        env=cluster.client_env,
    )


def finish(farm: subprocess.Popen) -> str:
    try:
        _, stderr = farm.communicate(timeout=FARM_TIMEOUT_SECONDS)
    except subprocess.TimeoutExpired:
        farm.kill()
        pytest.fail("the farm hung after the kill")
    assert farm.returncode == 0, stderr
    assert "error" not in stderr
    return stderr


@pytest.fixture(scope="module")
def long_reference(raytracer, tmp_path_factory):
    reference = tmp_path_factory.mktemp("reference") / "single.exr"
    render_single(raytracer, DEFAULT_SCENE, reference, *LONG_RENDER[:4])
    return reference


def test_a_worker_killed_mid_render(cluster, long_reference, tmp_path):
    output = tmp_path / "farm.exr"
    farm = start_long_render(cluster, output)
    preview = tmp_path / "farm.preview.png"
    previewed = False

    def kill_worker(worker, _):
        os.kill(worker, signal.SIGKILL)

    killed = kill_mid_part(farm, cluster.nodes[1], kill_worker)
    while farm.poll() is None and not previewed:
        previewed = preview.is_file()
        time.sleep(0.05)
    finish(farm)
    assert killed, "no part ran on the second node"
    assert ended(killed[1]), "the raytracer outlived its worker"
    assert previewed, "no preview while parts arrived"
    assert not preview.exists(), "the preview is removed at the end"
    assert_same_image(output, long_reference, LONG_SPP)


@pytest.fixture
def quickly_failing_cluster(raytracer):
    """Its own two nodes (one of them will die), whose head notices a dead
    node in a few seconds (Ray's default: about half a minute), yet not a
    live one that a loaded CI machine answers late."""
    health = {
        "RAY_health_check_period_ms": "500",
        "RAY_health_check_timeout_ms": "1000",
        "RAY_health_check_failure_threshold": "4",
    }
    with LocalCluster(
        nodes=2, cpus_per_node=1, env={"RTFARM_RAYTRACER": raytracer, **health}
    ) as cluster:
        yield cluster


def test_a_node_killed_mid_render(quickly_failing_cluster, long_reference, tmp_path):
    cluster = quickly_failing_cluster
    second = cluster.nodes[1]
    output = tmp_path / "farm.exr"
    farm = start_long_render(cluster, output)
    killed = kill_mid_part(farm, second, lambda worker, tracer: second.signal_all(signal.SIGKILL))
    finish(farm)
    assert killed, "no part ran on the second node"
    assert second.processes() == []
    assert_same_image(output, long_reference, LONG_SPP)


def test_a_broken_scene_stops_the_render_with_its_error(cluster, tmp_path):
    scene = tmp_path / "broken.json"
    scene.write_text(DEFAULT_SCENE.read_text().replace('"kd": 0.9', '"kd": "much"', 1))
    start = time.monotonic()
    done = run_farm(
        "render",
        "broken.json",
        "out.png",
        "--spp",
        8,
        "--tasks",
        8,
        "--size",
        "32x24",
        cluster=cluster,
        cwd=tmp_path,
    )
    assert done.returncode == 1
    assert one_error_line(done.stderr) == (
        "error: broken.json: scene.shapes[0].material.kd: expected a number, got string"
    )
    assert time.monotonic() - start < 60, "the render should stop at the first refusal"
    assert sorted(path.name for path in tmp_path.iterdir()) == ["broken.json"]


def test_a_driver_without_the_token_is_told_so(cluster, tmp_path):
    env = {
        name: value for name, value in cluster.client_env.items() if not name.startswith("RAY_AUTH")
    }
    env["HOME"] = str(tmp_path)  # no ~/.ray/auth_token either
    done = run_farm(
        "render", DEFAULT_SCENE, tmp_path / "out.png", "--address", cluster.address, env=env
    )
    assert done.returncode == 1
    assert one_error_line(done.stderr) == (
        f"error: the Ray cluster {cluster.address} refused this machine's token: set RAY_AUTH_MODE=token "
        "and the cluster's token (~/.ray/auth_token or RAY_AUTH_TOKEN)"
    )
    assert list(tmp_path.iterdir()) == []

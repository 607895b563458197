"""Shared by the farm's tests: the raytracer, a two-node local Ray cluster
(one CPU each, as CI has two), running rtfarm, and reading EXR images."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import OpenEXR
import pytest

from rtfarm.localcluster import LocalCluster

REPOSITORY = Path(__file__).resolve().parents[2]
DEFAULT_SCENE = REPOSITORY / "scenes" / "default.json"
AREA_LIGHT_SCENE = REPOSITORY / "scenes" / "study-arealight.json"
RTFARM = [sys.executable, "-m", "rtfarm"]
# Every farm command in these tests ends long before this; a hang fails.
FARM_TIMEOUT_SECONDS = 180


def raytracer_path() -> str:
    path = os.environ.get("RTFARM_RAYTRACER") or str(REPOSITORY / "build" / "raytracer")
    if not os.access(path, os.X_OK):
        pytest.fail(f"{path}: no raytracer binary (build with scripts/build.sh)")
    return path


@pytest.fixture(scope="session")
def raytracer() -> str:
    return raytracer_path()


@pytest.fixture(scope="session")
def cluster(raytracer):
    """A head and a second node on loopback, one CPU each, shared by the
    tests that need a cluster; stopped (every process of both) at the end."""
    with LocalCluster(nodes=2, cpus_per_node=1, env={"RTFARM_RAYTRACER": raytracer}) as started:
        yield started


def run_farm(
    *args, cluster=None, timeout: float = FARM_TIMEOUT_SECONDS, **popen
) -> subprocess.CompletedProcess:
    """rtfarm ARGS, on `cluster` (its address and token) when given."""
    if cluster is not None:
        args = (*args, "--address", cluster.address)
        popen["env"] = cluster.client_env
    return subprocess.run(
        [*RTFARM, *map(str, args)], capture_output=True, text=True, timeout=timeout, **popen
    )


def render_single(raytracer: str, scene, output, *args) -> None:
    """The single-machine render the farm's must equal."""
    subprocess.run([raytracer, str(scene), str(output), *map(str, args), "-q"], check=True)


def read_exr(path) -> np.ndarray:
    with OpenEXR.File(str(path)) as image:
        return np.array(image.channels()["RGBA"].pixels, dtype=np.float64)


def assert_same_image(farm_exr, single_exr, samples: int) -> None:
    """Equal up to float rounding, as `raytracer merge` promises, and every
    pixel carries all its samples (a lost part would leave fewer)."""
    farm, single = read_exr(farm_exr), read_exr(single_exr)
    assert farm.shape == single.shape
    assert np.all(farm[..., 3] == samples), f"sample counts {np.unique(farm[..., 3])}"
    scale = np.abs(single[..., :3]).max()
    assert scale > 0, "a black reference proves nothing"
    error = np.abs(farm[..., :3] - single[..., :3]).max() / scale
    # Parts sum their samples apart and the merge adds the sums: another order
    # of float32 additions, whose rounding can grow with the count (n units in
    # the last place at most; 1920 samples differed by 1.1e-5).
    tolerance = max(1e-5, samples * 2.0**-24)
    assert error <= tolerance, f"farm and single render differ by {error:.3g} (relative)"


def one_error_line(stderr: str) -> str:
    """The farm's one-line error (warnings aside)."""
    lines = [line for line in stderr.splitlines() if line and not line.startswith("warning: ")]
    lines = [line for line in lines if not line.startswith("rtfarm: ")]  # progress
    assert len(lines) == 1, f"expected one error line, got: {stderr!r}"
    assert lines[0].startswith("error: ")
    return lines[0]


_TETRAHEDRON_PLY = """ply
format ascii 1.0
element vertex 4
property float x
property float y
property float z
element face 4
property list uchar int vertex_indices
end_header
0 1 0
-1 -1 1
1 -1 1
0 -1 -1
3 0 1 2
3 0 2 3
3 0 3 1
3 1 3 2
"""

_SCENE_WITH_FILES = """{"nbounces": 2,
 "camera": {"type": "pinhole", "width": 32, "height": 24, "fov": 45,
            "position": [0, 0, 0], "lookat": [0, 0, -1], "up": [0, 1, 0]},
 "scene": {"backgroundcolor": [0.1, 0.1, 0.1],
   "lightsources": [{"type": "pointlight", "position": [0, 1.5, -0.5], "is": [60, 60, 60], "id": [60, 60, 60]}],
   "shapes": [
     {"id": "textured ball", "type": "sphere", "center": [-0.8, 0, -3], "radius": 0.7,
      "material": {"ks": 0.2, "kd": 0.8, "specularexponent": 10, "diffusecolor": [0.8, 0.2, 0.2],
                   "tPath": "../textures/check.ppm"}},
     {"id": "mesh", "type": "trimesh", "plyPath": "mesh.ply", "center": [0.9, 0, -3], "sizeScale": 0.6,
      "material": {"ks": 0.2, "kd": 0.8, "specularexponent": 10, "diffusecolor": [0.2, 0.6, 0.9]}}]}}
"""


def checker_ppm(side: int = 8) -> bytes:
    pixels = bytes(
        255 if (x + y) % 2 else 40 for y in range(side) for x in range(side) for _ in range(3)
    )
    return f"P6 {side} {side} 255\n".encode() + pixels


def write_scene_with_files(root: Path) -> Path:
    """A scene in a subfolder whose mesh is in the folder above and whose
    texture is named as seen from a build folder inside its own ("../textures/",
    found in its own textures/): the loader's three places to look."""
    scene_folder = root / "project" / "scenes" / "sub"
    (scene_folder / "textures").mkdir(parents=True)
    (scene_folder.parent / "mesh.ply").write_text(_TETRAHEDRON_PLY)
    (scene_folder / "textures" / "check.ppm").write_bytes(checker_ppm())
    scene = scene_folder / "scene.json"
    scene.write_text(_SCENE_WITH_FILES)
    return scene

"""Stills on a two-node local cluster equal single-machine renders."""

import re

import numpy as np
import pytest

from conftest import (
    AREA_LIGHT_SCENE,
    DEFAULT_SCENE,
    assert_same_image,
    read_exr,
    render_single,
    run_farm,
    write_scene_with_files,
)

PROGRESS_DONE = re.compile(
    r"^rtfarm: (\d+)/(\d+) tasks, 0 running, [0-9.e+-]+ Msamples/s, done in \d+ s$", re.MULTILINE
)


def farm_render(cluster, scene, output, *args):
    done = run_farm("render", scene, output, *args, cluster=cluster)
    assert done.returncode == 0, done.stderr
    return done


def test_the_default_scene_in_sample_ranges(cluster, raytracer, tmp_path):
    done = farm_render(
        cluster, DEFAULT_SCENE, tmp_path / "farm.exr", "--size", "32x24", "--spp", 8, "--tasks", 4
    )
    render_single(raytracer, DEFAULT_SCENE, tmp_path / "single.exr", "--size", "32x24", "--spp", 8)
    assert_same_image(tmp_path / "farm.exr", tmp_path / "single.exr", 8)
    # One progress line for the cluster, ending with every task done.
    assert PROGRESS_DONE.findall(done.stderr)[-1] == ("4", "4"), done.stderr
    assert not list(tmp_path.glob("*.preview.png")), "the preview is removed at the end"


def test_tiles_when_the_tasks_outnumber_the_samples(cluster, raytracer, tmp_path):
    done = farm_render(
        cluster,
        DEFAULT_SCENE,
        tmp_path / "farm.exr",
        "--size",
        "32x24",
        "--spp",
        2,
        "--tasks",
        6,
        "--seed",
        7,
    )
    render_single(
        raytracer,
        DEFAULT_SCENE,
        tmp_path / "single.exr",
        "--size",
        "32x24",
        "--spp",
        2,
        "--seed",
        7,
    )
    assert_same_image(tmp_path / "farm.exr", tmp_path / "single.exr", 2)
    assert PROGRESS_DONE.findall(done.stderr)[-1] == ("6", "6")  # 2 ranges x 3 tiles


@pytest.mark.parametrize("option", ["--light-samples", "--light-split"])
def test_light_options_reach_every_part(cluster, raytracer, tmp_path, option):
    """--light-samples and --light-split go to every part: the farm's image is the single
    render's with the option, which differs from the scene's own (other shadow rays; with
    --light-samples also another image, since coursework shading clamps each hit's summed
    light)."""
    size = ["--size", "32x24", "--spp", 4]
    farm_render(cluster, AREA_LIGHT_SCENE, tmp_path / "farm.exr", *size, "--tasks", 2, option, 3)
    render_single(raytracer, AREA_LIGHT_SCENE, tmp_path / "three.exr", *size, option, 3)
    render_single(raytracer, AREA_LIGHT_SCENE, tmp_path / "one.exr", *size)
    assert_same_image(tmp_path / "farm.exr", tmp_path / "three.exr", 4)
    three, one = read_exr(tmp_path / "three.exr"), read_exr(tmp_path / "one.exr")
    assert np.abs(three[..., :3] - one[..., :3]).max() > 1e-2 * np.abs(one[..., :3]).max()


def test_mode_and_bounces_reach_every_part(cluster, raytracer, tmp_path):
    """--mode and --bounces go to every part: the default scene path-traced two bounces deep,
    not as its file says (Whitted, four bounces)."""
    size = ["--size", "32x24", "--spp", 4]
    options = ["--mode", "pathtracer", "--bounces", 2]
    farm_render(cluster, DEFAULT_SCENE, tmp_path / "farm.exr", *size, "--tasks", 2, *options)
    render_single(raytracer, DEFAULT_SCENE, tmp_path / "traced.exr", *size, *options)
    render_single(raytracer, DEFAULT_SCENE, tmp_path / "whitted.exr", *size)
    assert_same_image(tmp_path / "farm.exr", tmp_path / "traced.exr", 4)
    traced, whitted = read_exr(tmp_path / "traced.exr"), read_exr(tmp_path / "whitted.exr")
    assert np.abs(traced[..., :3] - whitted[..., :3]).max() > 1e-2


def test_meshes_and_textures_travel_with_the_scene(cluster, raytracer, tmp_path):
    scene = write_scene_with_files(tmp_path)
    farm_render(
        cluster, scene, tmp_path / "farm.exr", "--spp", 6, "--tasks", 3, "--sampler", "sobol"
    )
    render_single(raytracer, scene, tmp_path / "single.exr", "--spp", 6, "--sampler", "sobol")
    assert_same_image(tmp_path / "farm.exr", tmp_path / "single.exr", 6)


def test_eight_bit_output_has_the_scenes_own_bytes(cluster, raytracer, tmp_path):
    """The default scene is family B, whose bytes are truncated, not rounded."""
    farm_render(
        cluster, DEFAULT_SCENE, tmp_path / "farm.ppm", "--size", "32x24", "--spp", 4, "--tasks", 2
    )
    render_single(raytracer, DEFAULT_SCENE, tmp_path / "single.ppm", "--size", "32x24", "--spp", 4)
    farm = np.frombuffer((tmp_path / "farm.ppm").read_bytes(), np.uint8).astype(int)
    single = np.frombuffer((tmp_path / "single.ppm").read_bytes(), np.uint8).astype(int)
    assert farm.shape == single.shape
    # A float rounding may move a byte across a step; a wrong curve moves many.
    assert np.abs(farm - single).max() <= 1 and np.count_nonzero(farm != single) <= 2

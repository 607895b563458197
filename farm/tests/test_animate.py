"""A camera path's frames, spread over the cluster, equal single renders."""

from conftest import DEFAULT_SCENE, assert_same_image, render_single, run_farm

PATH = "orbit 25 0\nwait 1\nzoom 2\norbit -10 5\n"  # 5 frames; 0 and 1 alike


def test_frames_of_a_camera_path(cluster, raytracer, tmp_path):
    (tmp_path / "orbit.path").write_text(PATH)
    frames = tmp_path / "frames"
    done = run_farm(
        "animate",
        DEFAULT_SCENE,
        tmp_path / "orbit.path",
        frames,
        "--frames",
        "1:4",
        "--name",
        "f%02d.exr",
        "--size",
        "32x24",
        "--spp",
        4,
        "--tasks-per-frame",
        2,
        cluster=cluster,
    )
    assert done.returncode == 0, done.stderr
    assert sorted(path.name for path in frames.iterdir()) == ["f01.exr", "f02.exr", "f03.exr"]
    assert "6/6 tasks" in done.stderr
    for frame in (1, 2, 3):
        single = tmp_path / f"single{frame}.exr"
        render_single(
            raytracer,
            DEFAULT_SCENE,
            single,
            "--size",
            "32x24",
            "--spp",
            4,
            "--camera-path",
            tmp_path / "orbit.path",
            "--frame",
            frame,
        )
        assert_same_image(frames / f"f{frame:02d}.exr", single, 4)

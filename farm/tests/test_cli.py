"""Bad input gets what the raytracer's CLI gives: one error line, a non-zero
exit, no output file, and no cluster asked for anything."""

import re

import pytest

from conftest import DEFAULT_SCENE, one_error_line, run_farm

# Nothing listens here: a command that got as far as the cluster would fail
# with a different message.
NO_CLUSTER = ["--address", "127.0.0.1:1"]


def outputs(folder):
    return sorted(path.name for path in folder.iterdir() if path.name.startswith("out"))


@pytest.mark.parametrize(
    "name,arguments,status,message",
    [
        (
            "missing scene",
            ["render", "nope.json", "{out}.png"],
            1,
            r"^error: nope\.json: cannot open scene: No such file or directory$",
        ),
        (
            "unknown format",
            ["render", "{scene}", "{out}.tga"],
            1,
            r"^error: .*out\.tga: unsupported output format \(use \.png, \.jpg, \.ppm, \.exr or \.hdr\)$",
        ),
        (
            "missing folder",
            ["render", "{scene}", "{tmp}/none/out.png"],
            1,
            r"^error: .*none/out\.png: folder .*none does not exist$",
        ),
        (
            "zero samples",
            ["render", "{scene}", "{out}.png", "--spp", "0"],
            2,
            r"^error: argument --spp: expected a whole number 1\.\.1048576, got '0' \(see rtfarm render --help\)$",
        ),
        ("bad size", ["render", "{scene}", "{out}.png", "--size", "32by24"], 2, r"argument --size"),
        (
            "zero light samples",
            ["render", "{scene}", "{out}.png", "--light-samples", "0"],
            2,
            r"^error: argument --light-samples: expected a whole number 1\.\.4096, got '0'",
        ),
        (
            "too many light replicas",
            ["render", "{scene}", "{out}.png", "--light-split", "65"],
            2,
            r"^error: argument --light-split: expected a whole number 1\.\.64, got '65'",
        ),
        (
            "unknown sampler",
            ["render", "{scene}", "{out}.png", "--sampler", "halton"],
            2,
            r"argument --sampler",
        ),
        (
            "preview is the output",
            ["render", "{scene}", "{out}.png", "--preview", "{out}.png"],
            1,
            r"the preview cannot be the output",
        ),
        (
            "missing raytracer",
            ["render", "{scene}", "{out}.png", "--raytracer", "{tmp}/nothing"],
            1,
            r"^error: .*nothing: raytracer binary not found on .* \(build it with scripts/build\.sh",
        ),
        (
            "missing camera path",
            ["animate", "{scene}", "nope.path", "{tmp}/frames"],
            1,
            r"^error: nope\.path: cannot open camera path: No such file or directory$",
        ),
        (
            "broken camera path",
            ["animate", "{scene}", "{tmp}/broken.path", "{tmp}/frames"],
            1,
            r"^error: .*broken\.path:2: unknown step 'spin'$",
        ),
        (
            "frames past the path",
            ["animate", "{scene}", "{tmp}/good.path", "{tmp}/frames", "--frames", "0:9"],
            1,
            r"^error: --frames 0:9: .*good\.path has 2 frame\(s\)$",
        ),
        (
            "frame names in a missing folder",
            ["animate", "{scene}", "{tmp}/good.path", "{tmp}/frames", "--name", "sub/f%d.png"],
            1,
            r"^error: .*frames/sub/f0\.png: folder .*frames/sub does not exist$",
        ),
        (
            "frame names without a number",
            ["animate", "{scene}", "{tmp}/good.path", "{tmp}/frames", "--name", "f.png"],
            1,
            r"^error: --name f\.png: needs one %d for the frame number$",
        ),
    ],
)
def test_bad_input(tmp_path, name, arguments, status, message):
    (tmp_path / "broken.path").write_text("orbit 1 2\nspin 3\n")
    (tmp_path / "good.path").write_text("orbit 10 0\nzoom 1\n")
    values = {"scene": DEFAULT_SCENE, "out": tmp_path / "out", "tmp": tmp_path}
    done = run_farm(
        *[argument.format(**values) for argument in arguments],
        *NO_CLUSTER,
        cwd=tmp_path,
        timeout=60
    )
    assert done.returncode == status, done.stderr
    assert re.search(message, one_error_line(done.stderr)), done.stderr
    assert outputs(tmp_path) == []
    assert not (tmp_path / "frames").exists() or not any((tmp_path / "frames").iterdir())


def test_an_unreachable_cluster_is_one_error_line(tmp_path):
    done = run_farm("render", DEFAULT_SCENE, tmp_path / "out.png", *NO_CLUSTER, timeout=120)
    assert done.returncode == 1
    assert "cannot connect to the Ray cluster 127.0.0.1:1" in one_error_line(done.stderr)
    assert outputs(tmp_path) == []

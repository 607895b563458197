"""What the driver ships to the workers: the scene and every file it uses."""

import json
import os
import struct

import pytest

from conftest import assert_same_image, render_single, write_scene_with_files
from rtfarm.bundle import make_bundle, referenced_files, scene_defaults, unpack
from rtfarm.errors import FarmError


def test_files_are_found_where_the_loader_looks(tmp_path):
    scene = write_scene_with_files(tmp_path)
    found = referenced_files(scene, scene.read_bytes())
    assert found == [scene.parent / "textures" / "check.ppm", scene.parent.parent / "mesh.ply"]


def test_the_bundle_keeps_the_layout_relative_to_the_files_common_folder(tmp_path):
    scene = write_scene_with_files(tmp_path)
    bundle = make_bundle(str(scene))
    assert bundle.scene == "sub/scene.json"
    assert sorted(bundle.files) == ["mesh.ply", "sub/scene.json", "sub/textures/check.ppm"]
    assert bundle.files["mesh.ply"] == (scene.parent.parent / "mesh.ply").read_bytes()


def test_an_unpacked_bundle_renders_as_the_original(tmp_path, raytracer):
    scene = write_scene_with_files(tmp_path / "here")
    bundle = make_bundle(str(scene))
    unpacked = unpack(bundle, tmp_path / "there")
    render_single(raytracer, scene, tmp_path / "here.exr", "--spp", 2)
    render_single(raytracer, unpacked, tmp_path / "there.exr", "--spp", 2)
    assert_same_image(tmp_path / "there.exr", tmp_path / "here.exr", 2)


def test_a_missing_texture_is_left_for_the_renderer_to_report(tmp_path):
    scene = write_scene_with_files(tmp_path)
    os.remove(scene.parent / "textures" / "check.ppm")
    assert sorted(make_bundle(str(scene)).files) == ["mesh.ply", "sub/scene.json"]


def test_absolute_paths_are_refused_with_the_file_named(tmp_path):
    scene = write_scene_with_files(tmp_path)
    text = scene.read_text().replace(
        '"mesh.ply"', json.dumps(str(scene.parent.parent / "mesh.ply"))
    )
    scene.write_text(text)
    with pytest.raises(FarmError, match=r"scene\.json: '/.*mesh\.ply' is an absolute path"):
        make_bundle(str(scene))


def test_gltf_buffers_and_images_are_found_by_uri(tmp_path):
    (tmp_path / "my buffer.bin").write_bytes(b"\0" * 8)
    (tmp_path / "images").mkdir()
    (tmp_path / "images" / "base.png").write_bytes(b"png")
    document = {
        "buffers": [
            {"uri": "my%20buffer.bin"},
            {"uri": "data:application/octet-stream;base64,AA=="},
        ],
        "images": [{"uri": "images/base.png"}],
    }
    gltf = tmp_path / "model.gltf"
    gltf.write_text(json.dumps(document))
    expected = [tmp_path / "my buffer.bin", tmp_path / "images" / "base.png"]
    assert referenced_files(gltf, gltf.read_bytes()) == expected
    chunk = json.dumps(document).encode().ljust(4 * ((len(json.dumps(document)) + 3) // 4))
    glb = tmp_path / "model.glb"
    glb.write_bytes(
        b"glTF"
        + struct.pack("<II", 2, 20 + len(chunk))
        + struct.pack("<II", len(chunk), 0x4E4F534A)
        + chunk
    )
    assert referenced_files(glb, glb.read_bytes()) == expected


def test_scene_defaults_read_the_sample_count_and_size(tmp_path):
    scene = write_scene_with_files(tmp_path)
    defaults = scene_defaults(make_bundle(str(scene)))
    assert (defaults.spp, defaults.width, defaults.height) == (16, 32, 24)
    scene.write_text(scene.read_text().replace('"nbounces": 2', '"nbounces": 2, "nsamples": 9'))
    assert scene_defaults(make_bundle(str(scene))).spp == 9


def test_an_unreadable_scene_is_named_as_given(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(
        FarmError, match=r"^nope\.json: cannot open scene: No such file or directory$"
    ):
        make_bundle("nope.json")

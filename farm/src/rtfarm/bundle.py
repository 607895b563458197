"""The scene file and every file it references, packed for the object store.

Workers share no file system with the driver, so the driver reads the
scene, its meshes and textures (and a camera path) into a Bundle, places it
in Ray's object store once, and each task writes it into a private folder
with the same relative layout, so the scene's relative paths resolve there
as they do here.

Which files a scene references: every string in the scene's JSON (any key,
so that all of the loader's aliases are covered: plyPath, mPath, file,
path, tPath, texture, ...) that names a regular file where the loader
looks (src/scene/SceneLoader.cpp, resolveRelative): next to the scene,
then in the folder above it, then as seen from a folder inside the scene's
("../textures/x.jpg"). glTF files name theirs by `uri`, relative to the
file (percent-encoded; `data:` URIs are embedded). A string that happens
to name a file that is not used only costs its bytes in the bundle.
"""

from __future__ import annotations

import json
import os
import struct
import urllib.parse
from dataclasses import dataclass
from pathlib import Path

from rtfarm.errors import FarmError

# Longer strings are data (base64 buffers), never file names.
_MAX_NAME_LENGTH = 4096


@dataclass(frozen=True)
class Bundle:
    scene: str  # the scene's path inside the bundle (POSIX, relative)
    files: dict[str, bytes]  # bundle path -> content, the scene included
    camera_path: bytes | None = None  # a viewer camera path (rtfarm animate)
    camera_path_name: str = ""  # as the user wrote it (messages)
    # What a bundle path looks like to the user ("scenes/" for "scenes/x.json"),
    # so that the workers' messages name the user's files.
    display_prefix: str = ""

    def size(self) -> int:
        return sum(map(len, self.files.values())) + len(self.camera_path or b"")


def _candidates(written: str, scene_dir: Path) -> list[Path]:
    """Where the loader looks for a file the scene names, in its order."""
    path = Path(written)
    found = [scene_dir / path, scene_dir.parent / path]
    if path.parts and path.parts[0] == ".." and len(path.parts) > 1:
        found.append(scene_dir.joinpath(*path.parts[1:]))
    return [Path(os.path.normpath(candidate)) for candidate in found]


def _first_file(candidates: list[Path]) -> Path | None:
    for candidate in candidates:
        try:
            if candidate.is_file():
                return candidate
        except OSError:  # a name too long for the file system, say
            continue
    return None


def _strings(value: object):
    """Every string in a JSON document, keys aside."""
    if isinstance(value, str):
        yield value
    elif isinstance(value, dict):
        for item in value.values():
            yield from _strings(item)
    elif isinstance(value, list):
        for item in value:
            yield from _strings(item)


def _glb_json(data: bytes) -> object | None:
    """The JSON chunk of a binary glTF (.glb), or None if it has none."""
    if len(data) < 20 or data[:4] != b"glTF":
        return None
    length, kind = struct.unpack_from("<II", data, 12)
    if kind != 0x4E4F534A:  # "JSON"
        return None
    return json.loads(data[20 : 20 + length])


def _document(scene: Path, data: bytes) -> object | None:
    """The scene's JSON; None where it is not JSON (the renderer will say why)."""
    try:
        if scene.suffix.lower() == ".glb":
            return _glb_json(data)
        return json.loads(data)
    except (ValueError, UnicodeDecodeError):
        return None


def _gltf_uris(document: object, gltf_dir: Path) -> list[Path]:
    """Buffers and images a glTF names by relative URI."""
    if not isinstance(document, dict):
        return []
    found = []
    for kind in ("buffers", "images"):
        for entry in document.get(kind) or []:
            uri = entry.get("uri") if isinstance(entry, dict) else None
            if isinstance(uri, str) and not uri.startswith("data:"):
                path = _first_file([Path(os.path.normpath(gltf_dir / urllib.parse.unquote(uri)))])
                if path:
                    found.append(path)
    return found


def referenced_files(scene: Path, data: bytes) -> list[Path]:
    """The files a scene (already read as `data`) makes the renderer read."""
    scene_dir = scene.parent
    document = _document(scene, data)
    if scene.suffix.lower() in (".gltf", ".glb"):
        return _gltf_uris(document, scene_dir)
    found: list[Path] = []
    for written in _strings(document):
        if not written or len(written) > _MAX_NAME_LENGTH or "\0" in written:
            continue
        path = _first_file(_candidates(written, scene_dir))
        if path is None:
            continue
        if os.path.isabs(written):
            raise FarmError(
                f"{scene}: '{written}' is an absolute path, which workers cannot see: "
                "make it relative to the scene's folder"
            )
        if path != scene and path not in found:
            found.append(path)
    return found


def _read(path: Path, what: str, shown: str | None = None) -> bytes:
    """The file's bytes; FarmError naming it as `shown` (default: its path)."""
    try:
        return path.read_bytes()
    except OSError as error:
        raise FarmError(f"{shown or path}: cannot open {what}: {error.strerror}") from None


def _display_prefix(root: Path) -> str:
    """How the bundle's root folder is written in messages: relative to here
    when it lies below the current folder, absolute otherwise."""
    relative = os.path.relpath(root)
    if relative == ".":
        return ""
    if relative.startswith(".."):
        return str(root) + "/"
    return relative + "/"


def make_bundle(scene_path: str, camera_path: str | None = None) -> Bundle:
    """Reads the scene, the files it references and the camera path."""
    scene = Path(os.path.normpath(os.path.abspath(scene_path)))
    scene_data = _read(scene, "scene", scene_path)
    references = referenced_files(scene, scene_data)
    root = Path(os.path.commonpath([scene.parent, *(path.parent for path in references)]))
    files = {scene.relative_to(root).as_posix(): scene_data}
    for path in references:
        files[path.relative_to(root).as_posix()] = _read(path, "file")
    camera = _read(Path(camera_path), "camera path", camera_path) if camera_path else None
    return Bundle(
        scene=scene.relative_to(root).as_posix(),
        files=files,
        camera_path=camera,
        camera_path_name=camera_path or "",
        display_prefix=_display_prefix(root),
    )


def unpack(bundle: Bundle, folder: Path) -> Path:
    """Writes the bundle's files below `folder`; the scene's path there."""
    for name, data in bundle.files.items():
        target = folder / name
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(data)
    return folder / bundle.scene


@dataclass(frozen=True)
class SceneDefaults:
    """What a render of the scene does without --spp and --size."""

    spp: int
    width: int | None  # None: not known here (glTF: the renderer chooses)
    height: int | None


_DEFAULT_SPP = 16  # the raytracer's, without --spp or a scene value


def _whole(value: object) -> int | None:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    return int(value) if value == int(value) and value >= 1 else None


def scene_defaults(bundle: Bundle) -> SceneDefaults:
    """The sample count (`spp` | `nsamples` | `samples`, top level or camera)
    and the camera's size from a JSON scene; the raytracer's defaults else."""
    document = _document(Path(bundle.scene), bundle.files[bundle.scene])
    if not isinstance(document, dict) or bundle.scene.lower().endswith((".gltf", ".glb")):
        return SceneDefaults(_DEFAULT_SPP, None, None)
    camera = document.get("camera") if isinstance(document.get("camera"), dict) else {}
    spp = None
    for where in (document, camera):
        for key in ("spp", "nsamples", "samples"):
            spp = spp or _whole(where.get(key))
    return SceneDefaults(
        spp or _DEFAULT_SPP, _whole(camera.get("width")), _whole(camera.get("height"))
    )

"""The worker's side, without a cluster: reading the raytracer's messages
and clearing up after killed workers."""

import os

from rtfarm.plan import Part
from rtfarm.worker import _Messages, _remove_orphans


class Board:
    def __init__(self):
        self.reports = []
        self.report = self

    def remote(self, index, fraction):
        self.reports.append((index, fraction))


def test_messages_give_progress_samples_and_the_users_file_names():
    board = Board()
    part = Part(5, 0, 8, region=(0, 0, 32, 6), pixel_share=0.25)
    messages = _Messages(part, board, {"/tmp/rtfarm-part-1-x/scene/": "scenes/"})
    for line in [
        "warning: /tmp/rtfarm-part-1-x/scene/sub/a.json: scene.foo: unknown key",
        "progress  50%    4.0/8 spp     0.11 Msamples/s  ETA   0.0 s",
        "rendered 32x24 at 8 spp in 0.012 s (0.26 Msamples/s) on llvmpipe",
    ]:
        messages.read(line + "\n")
    assert board.reports == [(5, 0.5)]
    assert messages.pixel_samples == 32 * 24 * 0.25 * 8
    assert messages.warnings() == ["warning: scenes/sub/a.json: scene.foo: unknown key"]


def test_folders_of_dead_workers_are_removed(tmp_path, monkeypatch):
    monkeypatch.setenv("TMPDIR", str(tmp_path))
    import tempfile

    monkeypatch.setattr(tempfile, "tempdir", None)
    dead = tmp_path / "rtfarm-part-999999999-abc"
    alive = tmp_path / f"rtfarm-part-{os.getpid()}-def"
    for folder in (dead, alive):
        (folder / "scene").mkdir(parents=True)
    _remove_orphans()
    assert not dead.exists() and alive.exists()

"""Splitting renders into parts: every sample of every pixel exactly once."""

import pytest

from rtfarm.errors import FarmError
from rtfarm.plan import plan_animation, plan_still, split_evenly, tiles_for


def coverage(parts, width, height):
    """How many times each (pixel row, sample) pair is rendered."""
    counts = {}
    for part in parts:
        rows = (
            range(part.region[1], part.region[1] + part.region[3]) if part.region else range(height)
        )
        assert part.region is None or (part.region[0], part.region[2]) == (0, width)
        for row in rows:
            for sample in range(part.first_sample, part.end_sample):
                counts[(row, sample)] = counts.get((row, sample), 0) + 1
    return counts


def test_split_evenly_covers_the_range_in_near_equal_pieces():
    assert split_evenly(10, 3) == [(0, 3), (3, 6), (6, 10)]
    assert split_evenly(4, 4) == [(0, 1), (1, 2), (2, 3), (3, 4)]


@pytest.mark.parametrize(
    "spp,tasks,tiles", [(16, 4, 1), (16, 5, 1), (3, 8, None), (1, 6, None), (7, 7, 2)]
)
def test_still_parts_render_every_sample_of_every_pixel_once(spp, tasks, tiles):
    width, height = 32, 24
    tiles = tiles or tiles_for(tasks, spp)
    parts = plan_still(spp, tasks, tiles, width, height)
    counts = coverage(parts, width, height)
    assert set(counts) == {(row, sample) for row in range(height) for sample in range(spp)}
    assert set(counts.values()) == {1}
    assert sum(part.work for part in parts) == pytest.approx(spp)
    assert [part.index for part in parts] == list(range(len(parts)))


def test_tiles_appear_only_when_the_tasks_outnumber_the_samples():
    assert tiles_for(8, 16) == 1
    assert tiles_for(8, 3) == 3
    parts = plan_still(3, 8, tiles_for(8, 3), 32, 24)
    assert len(parts) == 9 and all(part.region for part in parts)
    # The first sample range of every tile comes first (an early full preview).
    assert {part.region for part in parts[:3]} == {part.region for part in parts}


def test_tiles_need_the_image_size():
    with pytest.raises(FarmError, match="--size"):
        plan_still(1, 4, 4, None, None)
    with pytest.raises(FarmError, match="only 3 rows"):
        plan_still(1, 4, 4, 32, 3)


def test_part_arguments_are_the_raytracer_options():
    part = plan_still(3, 8, 3, 32, 24)[1]
    assert part.raytracer_args() == ["--samples", "0:1", "--region", "0,8,32,8"]
    frame = plan_animation([4], 8, 2)[1]
    assert frame.raytracer_args() == ["--samples", "4:8", "--frame", "4"]


def test_animation_parts_go_frame_by_frame():
    parts = plan_animation([2, 3, 4], 10, 3)
    assert [part.frame for part in parts] == [2, 2, 2, 3, 3, 3, 4, 4, 4]
    assert [(p.first_sample, p.end_sample) for p in parts[:3]] == [(0, 3), (3, 6), (6, 10)]
    assert len(plan_animation([0], 2, 5)) == 2  # never more ranges than samples

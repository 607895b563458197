"""rtfarm: renders of the project's `raytracer` spread over a Ray cluster.

The farm is a thin client of the CLI: sample ranges (`--samples FROM:TO`),
tiles (`--region`) and camera-path frames (`--camera-path --frame`) are
rendered by `raytracer` on the workers and combined by `raytracer merge`
on the driver, which is exact because sampling is a pure function of
(pixel, sample index, dimension, seed).
"""

__version__ = "0.1.0"

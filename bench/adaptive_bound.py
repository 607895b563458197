"""How far adaptive sampling could go: sample allocations simulated on measured per-pixel errors.

For each scene it renders (with the renderer, as Radiance .hdr) a Sobol reference, uniform Sobol
renders of 1 to 16 samples with several seeds, and two one-sample pilot renders with other
seeds. From these it knows each pixel's true mean squared error (display values, clamped to
0..1 as `converge` measures them) after n samples, and asks what the image's RMSE would be if
each pixel, or each 8x8 tile, had been given n_i = max(1, round(c * sqrt(v_i))) samples, the
allocation that minimises the MSE for a mean count when the error falls as 1/n (README
"Adaptive sampling"), for several choices of v_i:

  uniform       every pixel the same count
  tile truth    v_i the tile's true one-sample MSE (the best a per-tile allocation can know)
  pixel truth   v_i the pixel's true one-sample MSE
  tile pairs    what the renderer's rounds plan with: the one-sample variance measured on the
                tile's two paired 4x2 blocks (half the squared difference of the two pilots),
                raised to a quarter of the noisiest neighbouring tile's
  pixel edges   tile pairs plus half the pixel's largest squared difference to one of its four
                neighbours in the first pilot (neighbour contrast: finds the edges and thin
                features that a tile's paired blocks miss)

Costs per sample (rays) are not modelled: the counts are samples, not seconds. Prints the RMSE of
each rule at a few mean counts and the mean count at which each reaches the target RMSEs
(log-log interpolation). Standard library only; about a minute a scene on two cores.

Usage: adaptive_bound.py [--raytracer PATH] [--size WxH] [--seeds K] [--out DIR] SCENE.json...
"""
import argparse
import math
import os
import subprocess
import sys

from adaptive_table import seconds_to  # bench/, beside this script

COUNTS = [1, 2, 3, 4, 6, 8, 12, 16]
MEANS = [1, 1.25, 1.5, 2, 3, 4, 6, 8]
TARGETS = [0.01, 0.005]
TILE = 8
NEIGHBOUR_SHARE = 0.25


def read_hdr(path):
    """Width, height and a flat list of (r, g, b) from a Radiance RGBE file (flat or RLE)."""
    data = open(path, "rb").read()
    pos = 0
    while True:
        end = data.index(b"\n", pos)
        line, pos = data[pos:end], end + 1
        if line.startswith(b"-Y"):
            parts = line.split()
            height, width = int(parts[1]), int(parts[3])
            break
    pixels = []
    for _ in range(height):
        if data[pos] == 2 and data[pos + 1] == 2:
            pos += 4
            channels = []
            for _ in range(4):
                row = bytearray()
                while len(row) < width:
                    n = data[pos]
                    pos += 1
                    if n > 128:
                        row.extend(bytes([data[pos]]) * (n - 128))
                        pos += 1
                    else:
                        row.extend(data[pos:pos + n])
                        pos += n
                channels.append(row)
            quads = zip(*channels)
        else:
            quads = [tuple(data[pos + 4 * x:pos + 4 * x + 4]) for x in range(width)]
            pos += 4 * width
        for r, g, b, e in quads:
            f = math.ldexp(1.0, e - 136) if e else 0.0
            pixels.append((r * f, g * f, b * f))
    return width, height, pixels


def displayed(path):
    width, height, pixels = read_hdr(path)
    clamp = lambda v: min(max(v, 0.0), 1.0)
    return width, height, [(clamp(r), clamp(g), clamp(b)) for r, g, b in pixels]


def squared(a, b):
    return ((a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2 + (a[2] - b[2]) ** 2) / 3


def render(args, scene, path, spp, seed):
    if os.path.exists(path):
        return
    subprocess.run([args.raytracer, scene, path, "--size", args.size, "--spp", str(spp),
                    "--sampler", "sobol", "--seed", str(seed), "-q"], check=True)


def paired_blocks(tile_x, tile_y):
    """adaptivePairedBlocks of shaders/gpu_types.h."""
    m = 0xFFFFFFFF
    h = ((tile_x * 0x9E3779B1) & m) ^ ((tile_y * 0x85EBCA77) & m)
    h ^= h >> 15
    h = (h * 0x2C1B3C6D) & m
    h ^= h >> 13
    first = h >> 29
    return first, first ^ (1 + ((h >> 26) & 3))


class Scene:
    def __init__(self, args, scene):
        name = os.path.splitext(os.path.basename(scene))[0]
        folder = os.path.join(args.out, name)
        os.makedirs(folder, exist_ok=True)
        self.name = name
        render(args, scene, os.path.join(folder, "reference.hdr"), 1024, 999)
        self.width, self.height, reference = displayed(os.path.join(folder, "reference.hdr"))
        pixels = self.width * self.height
        self.mse = {}  # count -> per-pixel mean squared error over the seeds
        for n in COUNTS:
            total = [0.0] * pixels
            for seed in range(1, args.seeds + 1):
                path = os.path.join(folder, f"sobol-{n}-{seed}.hdr")
                render(args, scene, path, n, seed)
                image = displayed(path)[2]
                for i in range(pixels):
                    total[i] += squared(image[i], reference[i])
            self.mse[n] = [t / args.seeds for t in total]
        pilots = []
        for seed in (args.seeds + 1, args.seeds + 2):
            path = os.path.join(folder, f"pilot-{seed}.hdr")
            render(args, scene, path, 1, seed)
            pilots.append(displayed(path)[2])
        self.pair_variance = [squared(a, b) / 2 for a, b in zip(*pilots)]
        self.contrast = self.neighbour_contrast(pilots[0])
        self.tiles = self.tile_pixels()

    def neighbour_contrast(self, image):
        w, h = self.width, self.height
        out = [0.0] * (w * h)
        for y in range(h):
            for x in range(w):
                i = y * w + x
                for nx, ny in ((x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)):
                    if 0 <= nx < w and 0 <= ny < h:
                        out[i] = max(out[i], squared(image[i], image[ny * w + nx]))
        return out

    def tile_pixels(self):
        """Per tile: (tile x, tile y, its pixels, its paired pixels)."""
        tiles = []
        for ty in range((self.height + TILE - 1) // TILE):
            for tx in range((self.width + TILE - 1) // TILE):
                blocks = paired_blocks(tx, ty)
                pixels, paired = [], []
                for y in range(ty * TILE, min(ty * TILE + TILE, self.height)):
                    for x in range(tx * TILE, min(tx * TILE + TILE, self.width)):
                        pixels.append(y * self.width + x)
                        if (y % TILE) // 2 * 2 + (x % TILE) // 4 in blocks:
                            paired.append(y * self.width + x)
                tiles.append((tx, ty, pixels, paired))
        return tiles

    def per_tile(self, values_of_tile):
        """A per-pixel list holding each tile's value."""
        out = [0.0] * (self.width * self.height)
        for tile in self.tiles:
            value = values_of_tile(tile)
            for i in tile[2]:
                out[i] = value
        return out

    def tiles_planned(self):
        """The rounds' tile noise: paired blocks, raised to a share of the noisiest neighbour."""
        own = {}
        for tx, ty, pixels, paired in self.tiles:
            measured = paired or pixels
            own[(tx, ty)] = sum(self.pair_variance[i] for i in measured) / len(measured)
        def dilated(tile):
            tx, ty = tile[0], tile[1]
            neighbour = max(own.get((tx + dx, ty + dy), 0.0) for dx in (-1, 0, 1) for dy in (-1, 0, 1))
            return max(own[(tx, ty)], NEIGHBOUR_SHARE * neighbour)
        return self.per_tile(dilated)

    def rules(self):
        truth = self.mse[1]
        tile_truth = self.per_tile(lambda t: sum(truth[i] for i in t[2]) / len(t[2]))
        planned = self.tiles_planned()
        edges = [v + g / 2 for v, g in zip(planned, self.contrast)]
        return {"tile truth": tile_truth, "pixel truth": truth, "tile pairs": planned,
                "pixel edges": edges}

    def mse_at(self, i, n):
        """Pixel i's MSE after n samples, log-log between the measured counts."""
        if n <= 1:
            return self.mse[1][i]
        for lo, hi in zip(COUNTS, COUNTS[1:]):
            if lo <= n <= hi:
                e0, e1 = max(self.mse[lo][i], 1e-12), max(self.mse[hi][i], 1e-12)
                f = math.log(n / lo) / math.log(hi / lo)
                return math.exp(math.log(e0) + f * math.log(e1 / e0))
        return self.mse[COUNTS[-1]][i] * COUNTS[-1] / n

    def rmse_uniform(self, mean):
        pixels = self.width * self.height
        return math.sqrt(sum(self.mse_at(i, mean) for i in range(pixels)) / pixels)

    def rmse_allocated(self, variance, mean):
        """RMSE when pixel i gets max(1, round(c * sqrt(v_i))), c spending `mean` on average."""
        pixels = len(variance)
        rates = [math.sqrt(v) for v in variance]
        counts = lambda c: [max(1, round(c * r)) for r in rates]
        lo, hi = 0.0, 1e7
        for _ in range(50):
            mid = (lo + hi) / 2
            if sum(counts(mid)) < mean * pixels:
                lo = mid
            else:
                hi = mid
        return math.sqrt(sum(self.mse_at(i, n) for i, n in enumerate(counts(lo))) / pixels)


def mean_to(curve, target):
    """The mean count where an RMSE curve [(mean, rmse)] crosses the target, log-log."""
    if curve[0][1] <= target:
        return f"<={curve[0][0]}"
    crossing = seconds_to(curve, target)  # the same interpolation over counts
    return f"{crossing:.2f}" if crossing else f">{curve[-1][0]}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser.add_argument("--raytracer", default=os.path.join(root, "build", "raytracer"))
    parser.add_argument("--size", default="320x240")
    parser.add_argument("--seeds", type=int, default=8)
    parser.add_argument("--out", default=os.path.join(root, "build", "adaptive-bound"))
    parser.add_argument("scenes", nargs="+")
    args = parser.parse_args()
    header = ["scene", "rule"] + [f"@{m}" for m in MEANS] + [f"to {t}" for t in TARGETS]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for path in args.scenes:
        scene = Scene(args, path)
        curves = {"uniform": [(m, scene.rmse_uniform(m)) for m in MEANS]}
        for rule, variance in scene.rules().items():
            curves[rule] = [(m, scene.rmse_allocated(variance, m)) for m in MEANS]
        for rule, curve in curves.items():
            cells = [scene.name, rule] + [f"{e:.4f}" for _, e in curve]
            cells += [mean_to(curve, t) for t in TARGETS]
            print("| " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    sys.exit(main())

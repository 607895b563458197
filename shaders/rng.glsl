// Counter-based random numbers: every value is a pure function of
// (pixel, sample index, dimension, seed), so a render can be split over
// dispatches, tiles or machines and still produce the same samples.
#ifndef RT_RNG_GLSL
#define RT_RNG_GLSL

// Random dimensions used by the kernels (each a pair of numbers).
#define RT_DIM_PIXEL 0u
#define RT_DIM_LENS 2u
#define RT_DIM_BRANCH 4u  // stochastic choices when the Whitted stack is full (per depth)

// Four rounds of mixing of a 4-component counter (a PCG-style hash: every
// input bit affects every output bit after the second round).
uvec4 hashCounter(uvec4 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.w;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v.w += v.y * v.z;
  v ^= v >> 16u;
  v.x += v.y * v.w;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v.w += v.y * v.z;
  v ^= v >> 16u;
  return v;
}

// Top 24 bits to a float in [0, 1): exact, never rounds up to 1.
float unitFloat(uint bits) { return float(bits >> 8u) * (1.0 / 16777216.0); }

vec2 randomPair(uint pixel, uint sampleIndex, uint dimension, uint seed) {
  uvec4 h = hashCounter(uvec4(pixel, sampleIndex, dimension, seed));
  return vec2(unitFloat(h.x), unitFloat(h.y));
}

// A bijection of [0, n) keyed by `key`: invertible mixing on the smallest
// power-of-two domain that holds n, walked until the value falls inside
// (cycle walking keeps it a permutation of exactly [0, n)).
uint permuteIndex(uint index, uint n, uint key) {
  uint mask = n - 1u;
  mask |= mask >> 1u;
  mask |= mask >> 2u;
  mask |= mask >> 4u;
  mask |= mask >> 8u;
  mask |= mask >> 16u;
  uint v = index;
  do {
    v ^= key & mask;
    v = (v * 0x2c1b3c6du) & mask;  // odd multiplier: bijective modulo 2^k
    v ^= (v & mask) >> 3u;
    v = (v * 0x297a2d39u) & mask;
    v ^= (v >> 5u) ^ ((key >> 16u) & mask);
    v = (v * 0x8ebc6af1u) & mask;
    v ^= v >> 7u;
  } while (v >= n);
  return v;
}

// Stratified 2D point for sample `s` of `count`: the unit square is cut
// into columns x rows >= count cells; each sample takes its own cell (in a
// per-pixel shuffled order) and, inside it, its own sub-column and sub-row
// (multi-jittered), so both projections are stratified too. Works for any
// count, not only squares.
vec2 jitteredPoint(uint s, uint count, uint key) {
  uint columns = uint(ceil(sqrt(float(count))));
  uint rows = (count + columns - 1u) / columns;
  uint cell = permuteIndex(s % count, count, key);
  uint cx = cell % columns;
  uint cy = cell / columns;
  uint subX = permuteIndex(cy, rows, key * 0x9e3779b9u + 1u);
  uint subY = permuteIndex(cx, columns, key * 0x85ebca6bu + 2u);
  uvec4 h = hashCounter(uvec4(s, count, key, 0x51ed27u));
  float x = (float(cx) + (float(subX) + unitFloat(h.x)) / float(rows)) / float(columns);
  float y = (float(cy) + (float(subY) + unitFloat(h.y)) / float(columns)) / float(rows);
  return min(vec2(x, y), vec2(0.99999994));
}

// The 2D sample of one dimension pair for (pixel, sample, seed).
vec2 samplePair(uint samplerKind, uint pixel, uint sampleIndex, uint samplesTotal, uint dimension,
                uint seed) {
  if (samplerKind == RT_SAMPLER_JITTERED && sampleIndex < samplesTotal) {
    uint key = hashCounter(uvec4(pixel, dimension, seed, 0x6a09e667u)).x;
    return jitteredPoint(sampleIndex, samplesTotal, key);
  }
  return randomPair(pixel, sampleIndex, dimension, seed);
}

#endif

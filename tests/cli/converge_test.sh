#!/usr/bin/env bash
# `raytracer converge` and --target-rmse from the command line: the CSV has a
# row per sampler and sample count, the plot is a PNG, a saved reference can
# be reused, bad arguments fail with one line and leave no files.
# Usage: converge_test.sh RAYTRACER SCENES_DIR SCRATCH_DIR
set -u
RAYTRACER=$1
SCENES=$2
SCRATCH=$3
rm -rf "$SCRATCH"
mkdir -p "$SCRATCH"
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

SCENE="$SCENES/study-thinlens.json"
COMMON=(--size 64x48 --region 8,28,24,16)

# --- a study over two samplers and three counts --------------------------
if "$RAYTRACER" converge "$SCENE" "${COMMON[@]}" --samplers random,sobol --spp-list 4,8,16 \
    --reference-spp 128 --clock cpu --estimate --out "$SCRATCH/study" >"$SCRATCH/stdout" 2>"$SCRATCH/stderr"; then
  pass
else
  fail "converge run: $(cat "$SCRATCH/stderr")"
fi
[[ "$(head -1 "$SCRATCH/study.csv")" == "sampler,samples,seconds,cpu_seconds,rmse,estimated_rmse" ]] && pass ||
  fail "CSV header: $(head -1 "$SCRATCH/study.csv")"
rows=$(tail -n +2 "$SCRATCH/study.csv" | cut -d, -f1,2 | tr '\n' ' ')
[[ "$rows" == "random,4 random,8 random,16 sobol,4 sobol,8 sobol,16 " ]] && pass ||
  fail "CSV rows: $rows"
# Every error is a positive number, and the error falls from 4 to 16 samples.
awk -F, 'NR > 1 && !($3 > 0 && $4 > 0 && $5 > 0 && $5 < 1 && $6 > 0) { bad = 1 } END { exit bad }' "$SCRATCH/study.csv" &&
  pass || fail "CSV values: $(cat "$SCRATCH/study.csv")"
awk -F, '$2 == 4 { first[$1] = $5 } $2 == 16 { last[$1] = $5 }
  END { for (s in first) if (!(last[s] < first[s])) exit 1 }' "$SCRATCH/study.csv" &&
  pass || fail "error does not fall: $(cat "$SCRATCH/study.csv")"
[[ "$(head -c 8 "$SCRATCH/study.png" | od -An -tx1 | tr -d ' \n')" == "89504e470d0a1a0a" ]] && pass ||
  fail "plot is not a PNG"
[[ -s "$SCRATCH/study-reference.exr" ]] && pass || fail "reference not saved"
grep -Eq '^sobol +-?[0-9.]+ ' "$SCRATCH/stdout" && grep -Eq '^sampler +slope' "$SCRATCH/stdout" &&
  pass || fail "summary table: $(cat "$SCRATCH/stdout")"

# --- adaptive sampling as a series beside the others ----------------------
if "$RAYTRACER" converge "$SCENE" --size 64x48 --samplers sobol,adaptive --spp-list 8,16 \
    --reference-spp 64 --out "$SCRATCH/adaptive" -q >"$SCRATCH/stdout" 2>"$SCRATCH/stderr"; then
  rows=$(tail -n +2 "$SCRATCH/adaptive.csv" | cut -d, -f1,2 | tr '\n' ' ')
  [[ "$rows" == "sobol,8 sobol,16 adaptive,8 adaptive,16 " ]] && pass || fail "adaptive CSV rows: $rows"
  # Adaptive renders always estimate their error.
  awk -F, '$1 == "adaptive" && !($6 > 0) { bad = 1 } END { exit bad }' "$SCRATCH/adaptive.csv" &&
    pass || fail "adaptive rows lack the estimate: $(cat "$SCRATCH/adaptive.csv")"
  grep -Eq '^adaptive +-?[0-9.]+ ' "$SCRATCH/stdout" && pass || fail "adaptive summary: $(cat "$SCRATCH/stdout")"
else
  fail "converge with adaptive: $(cat "$SCRATCH/stderr")"
fi

# --- the saved reference gives the same errors (and --repeat, whose ------
# --- medians are of times: the images are the same each time) -----------
if "$RAYTRACER" converge "$SCENE" "${COMMON[@]}" --samplers sobol --spp-list 4,8 --repeat 3 \
    --reference "$SCRATCH/study-reference.exr" --estimate --out "$SCRATCH/again" -q >/dev/null 2>&1; then
  [[ "$(grep '^sobol,8,' "$SCRATCH/again.csv" | cut -d, -f5)" == \
     "$(grep '^sobol,8,' "$SCRATCH/study.csv" | cut -d, -f5)" ]] && pass ||
    fail "errors against the saved reference differ"
else
  fail "converge with --reference"
fi

# --- errors: one line, non-zero status, no files -------------------------
# expect_error NAME PATTERN ARGS...: one error line, and no bad* files left.
expect_error() { expect_failure bad "$@"; }
expect_error "unknown sampler" "sampler" converge "$SCENE" --samplers random,halton --out "$SCRATCH/bad"
expect_error "region outside" "region 60,40,10,10 does not fit in the 64x48 image" \
  converge "$SCENE" --size 64x48 --region 60,40,10,10 --out "$SCRATCH/bad"
expect_error "malformed region" "--region 1,2,3: expected X,Y,WIDTH,HEIGHT" \
  converge "$SCENE" --region 1,2,3 --out "$SCRATCH/bad"
expect_error "reference of another size" "reference is 64x48 but the renders are 32x24" \
  converge "$SCENE" --size 32x24 --reference "$SCRATCH/study-reference.exr" --out "$SCRATCH/bad"
expect_error "both reference options" "excludes" converge "$SCENE" --reference "$SCRATCH/x.exr" \
  --reference-spp 64 --out "$SCRATCH/bad"
expect_error "one count" "at least two" converge "$SCENE" --spp-list 8 --out "$SCRATCH/bad"
expect_error "no repeats" "--repeat" converge "$SCENE" --repeat 0 --out "$SCRATCH/bad"

# --- render --target-rmse: stops early, reports the estimate -------------
if "$RAYTRACER" "$SCENE" "$SCRATCH/target.png" --size 48x36 --sampler sobol --target-rmse 0.02 \
    2>"$SCRATCH/stderr"; then
  grep -Eq 'estimated RMSE 0\.0(1[0-9]|0[0-9])[0-9]* \(target reached\)' "$SCRATCH/stderr" && pass ||
    fail "--target-rmse summary: $(tail -1 "$SCRATCH/stderr")"
else
  fail "--target-rmse run: $(cat "$SCRATCH/stderr")"
fi
# --spp still caps it: 4 samples cannot reach 0.0001.
"$RAYTRACER" "$SCENE" "$SCRATCH/capped.png" --size 48x36 --spp 4 --sampler sobol \
  --target-rmse 0.0001 2>"$SCRATCH/stderr" &&
  grep -q 'at 4 spp' "$SCRATCH/stderr" && ! grep -q 'target reached' "$SCRATCH/stderr" && pass ||
  fail "--spp with --target-rmse: $(cat "$SCRATCH/stderr")"

finish "converge tests"

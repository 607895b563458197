#!/usr/bin/env bash
# Fuzzes the loaders of untrusted files (JSON scenes, PLY meshes, glTF
# models) with libFuzzer under AddressSanitizer + UndefinedBehaviorSanitizer,
# each target for SECONDS (default 60), two targets at a time (one a core),
# seeded from ../shared. The corpus
# grows in build-asan/fuzz/corpus/<target> and is reused by the next run.
# A crash, sanitizer report, leak, timeout (10 s for one input) or memory
# blow-up (2 GiB) keeps its input in build-asan/fuzz/findings/<target>/ and
# fails the script; re-run that input alone with the printed command.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]   (targets: scene_json ply gltf obj)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
seconds=${1:-60}
shift || true
targets=("$@")
((${#targets[@]})) || targets=(scene_json ply gltf obj)
if ! [[ $seconds =~ ^[0-9]+$ ]] || ((seconds < 1)); then
  echo "fuzz.sh: SECONDS must be a positive integer, got '$seconds'" >&2
  exit 2
fi

bash "$root/scripts/build-sanitized.sh"
shared=$(cd "$root/.." && pwd)/shared
work=$root/build-asan/fuzz

# seed_files TARGET: the seed inputs (small enough to mutate quickly).
seed_files() {
  [[ -d $shared ]] || return 0
  case $1 in
    scene_json) find "$shared/scene-format" -name '*.json' -size -256k ;;
    ply) find "$shared/assets/ply" "$shared/scene-format" -name '*.ply' -size -128k ;;
    gltf) find "$shared/assets/gltf" "$shared/assets/gltf-invalid" \
      \( -name '*.gltf' -o -name '*.glb' \) -size -256k ;;
    obj) find "$root/assets/models" "$root/tests/fuzz/regressions/obj" -name '*.obj' ;;
  esac
}

# fuzz_target TARGET: one libFuzzer run; its summary line goes to
# $work/TARGET.summary, and it fails when the run found something.
fuzz_target() {
  local target=$1
  local binary=$work/fuzz_$target seeds=$work/seeds/$target corpus=$work/corpus/$target
  local findings=$work/findings/$target log=$work/$target.log
  rm -rf "$seeds"
  mkdir -p "$seeds" "$corpus" "$findings"
  # Copied under their content hash: seed names repeat across folders.
  while IFS= read -r file; do
    cp "$file" "$seeds/$(sha1sum "$file" | cut -c1-16)$(basename "$file" | sed 's/.*\(\.[^.]*\)$/\1/')"
  done < <(seed_files "$target")
  echo "fuzz $target: ${seconds}s, $(ls "$seeds" | wc -l) seeds, $(ls "$corpus" | wc -l) corpus inputs"
  local dictionary=()
  [[ -f $root/tests/fuzz/$target.dict ]] && dictionary=(-dict="$root/tests/fuzz/$target.dict")
  local status=0 started
  started=$(mktemp)
  ASAN_OPTIONS=abort_on_error=1:detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$binary" "$corpus" "$seeds" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="$findings/" -print_final_stats=1 -close_fd_mask=1 "${dictionary[@]}" >"$log" 2>&1 || status=$?
  local runs rate cov
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
  cov=$(grep -Eo 'cov: [0-9]+' "$log" | tail -1 | cut -d' ' -f2)
  printf '%-11s %10s runs %8s exec/s  cov %6s  status %s\n' "$target" "${runs:-?}" "${rate:-?}" \
    "${cov:-?}" "$status" >"$work/$target.summary"
  if ((status != 0)); then
    grep -E 'ERROR|SUMMARY|fuzz finding|runtime error|==[0-9]+==' "$log" | head -20 >&2 || true
    find "$findings" -type f -newer "$started" | while IFS= read -r input; do
      echo "reproduce: $binary $input" >&2
    done
    echo "fuzz $target FAILED (log: $log)" >&2
  fi
  rm -f "$started"
  return "$status"
}

for target in "${targets[@]}"; do
  [[ -x $work/fuzz_$target ]] || { echo "fuzz.sh: no fuzz target '$target'" >&2; exit 2; }
done
# Two targets at a time, one a core: each libFuzzer run is one process.
failed=0
pids=()
for target in "${targets[@]}"; do
  fuzz_target "$target" &
  pids+=($!)
  if ((${#pids[@]} == 2)); then
    wait "${pids[0]}" || failed=1
    pids=("${pids[1]}")
  fi
done
for pid in "${pids[@]}"; do wait "$pid" || failed=1; done
summary=()
for target in "${targets[@]}"; do summary+=("$(cat "$work/$target.summary")"); done
printf '%s\n' "target          executions   exec/s  coverage" "${summary[@]}"
exit $failed

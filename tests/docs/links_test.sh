#!/usr/bin/env bash
# The Markdown files' local links and images point at files that exist;
# every image in assets/readme/ is shown by one of them (an image the README
# stopped showing is deleted, not left to go stale); and every section that
# a source file cites as README "Section" is a heading of the README.
#   links_test.sh SOURCE_DIR
set -uo pipefail
shopt -s nullglob
root=${1:?usage: links_test.sh SOURCE_DIR}
cd "$root" || exit 1
failures=0
shown=$(mktemp)
trap 'rm -f "$shown"' EXIT

# Local targets of Markdown links and images, and of <img src="...">.
link_targets() {  # FILE
  grep -o -E '\]\([^)[:space:]]+\)|<img [^>]*src="[^"]+"' "$1" |
    sed -E 's/^\]\(//; s/\)$//; s/^<img [^>]*src="//; s/"$//' |
    grep -v -E '^[a-z]+:|^#' | sed 's/#.*//'
}

while IFS= read -r markdown; do
  folder=$(dirname "$markdown")
  while IFS= read -r target; do
    [[ -z $target ]] && continue
    path=$folder/$target
    if [[ -e $path ]]; then
      realpath --relative-to=. "$path" >>"$shown"
    else
      echo "FAIL: $markdown links to $target, which does not exist"
      failures=$((failures + 1))
    fi
  done < <(link_targets "$markdown")
done < <(git ls-files '*.md' 2>/dev/null || find . -name '*.md' -not -path './build*')

for image in assets/readme/*; do
  if ! grep -qx "$image" "$shown"; then
    echo "FAIL: $image is shown by no Markdown file"
    failures=$((failures + 1))
  fi
done

# Sections cited from the sources, a comment's line break allowed between
# README and the name; a heading matches when it starts with the name.
while IFS= read -r section; do
  if ! grep -q -E "^#+ $(printf '%s' "$section" | sed 's/[][().*^$]/\\&/g')" README.md; then
    echo "FAIL: the sources cite README \"$section\", which is no heading of README.md"
    failures=$((failures + 1))
  fi
done < <(git ls-files src shaders tests bench scripts farm 2>/dev/null | grep -v '^tests/docs/' |
  xargs perl -0777 -ne 'while (/README\s*(?:\/\/|#|\*)?\s*["\x27]([A-Z][^"\x27\n]+)["\x27]/g) { print "$1\n" }' |
  sort -u)

if ((failures > 0)); then
  echo "$failures broken or unused"
  exit 1
fi
echo "docs: local links resolve, every README image is shown, every cited section exists"

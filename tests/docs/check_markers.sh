#!/bin/sh
# doc_snippets.py's markers: a skip block is not extracted, a release-only block is extracted with
# the label the sanitizer stage leaves out, an unmarked block plainly, a misspelt marker is refused.
# usage: check_markers.sh PYTHON SCRIPT WORKDIR
set -eu
python="$1" script="$2" dir="$3"
rm -rf "$dir" && mkdir -p "$dir"
cat >"$dir/page.md" <<'MD'
<!-- doc-test: skip (illustrative) -->
```sh
echo skipped
```
<!-- doc-test: release-only (slow under the sanitizers) -->
```sh
echo slow
```
```sh
echo plain
```
MD
"$python" "$script" extract --out "$dir/out" --cmake "$dir/calls.cmake" --root "$dir" "$dir/page.md"
calls="$(grep -c '^fuzzypid_doc_snippet' "$dir/calls.cmake")"
[ "$calls" = 2 ] || { echo "want 2 blocks extracted, got $calls"; exit 1; }
grep -q '^fuzzypid_doc_snippet(page_md_6 sh ".*" release-only)$' "$dir/calls.cmake" ||
  { echo "the release-only block lacks its label"; cat "$dir/calls.cmake"; exit 1; }
grep -q '^fuzzypid_doc_snippet(page_md_9 sh "[^"]*")$' "$dir/calls.cmake" ||
  { echo "the plain block is not extracted plainly"; cat "$dir/calls.cmake"; exit 1; }
printf '<!-- doc-test: release_only (typo) -->\n```sh\necho x\n```\n' >"$dir/bad.md"
if "$python" "$script" extract --out "$dir/out2" --cmake "$dir/bad.cmake" --root "$dir" \
  "$dir/bad.md" 2>"$dir/err"; then
  echo "a misspelt marker was accepted"
  exit 1
fi
grep -q 'bad.md:1: malformed doc-test marker' "$dir/err" || { cat "$dir/err"; exit 1; }
echo "markers ok"

#!/usr/bin/env bash
# Shows that two revisions bake byte-identical outputs: builds brdfbake at REV (default
# HEAD) in a scratch worktree and from the current tree, bakes every default preset in every
# format with both, and compares every file's SHA-256. Sidecars are compared twice: as bytes,
# and without `quadrature.method` (the text describing how the texels were computed, which a
# refactor that retires an unused method rewrites) and the digests that follow from it. Exit 0
# when every texture, preview and source file is identical and every sidecar is identical but
# for those fields, 1 (listing the differences) otherwise.
#
#   scripts/same-outputs.sh            # the working tree against HEAD
#   scripts/same-outputs.sh 3c65ad6    # against another commit
#   scripts/same-outputs.sh REV PRESET.json ...   # other presets (paths) instead of the defaults
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:-HEAD}
shift || true
scratch=target/same-outputs
rm -rf "$scratch/a" "$scratch/b"
mkdir -p "$scratch"
if [ -e "$scratch/worktree" ]; then git worktree remove --force "$scratch/worktree"; fi
git worktree add --detach "$scratch/worktree" "$rev" >/dev/null
trap 'git worktree remove --force "$scratch/worktree" >/dev/null 2>&1 || true' EXIT
echo "building $rev ..." >&2
cargo build --release --quiet --bin brdfbake --manifest-path "$scratch/worktree/Cargo.toml" \
    --target-dir "$scratch/target"
echo "building the working tree ..." >&2
cargo build --release --quiet --bin brdfbake
formats=exr,ktx2,png,h,rs,glsl,hlsl,wgsl
presets=("$@")
# (the revision bakes the working tree's presets/, so both bake the same inputs)
"$scratch/target/release/brdfbake" bake -q --format "$formats" --out "$scratch/a" "${presets[@]}"
target/release/brdfbake bake -q --format "$formats" --out "$scratch/b" "${presets[@]}"
digests() { (cd "$1" && find . -type f | LC_ALL=C sort | xargs sha256sum); }
# every sidecar without quadrature.method, sidecar_digest and its own digest entry
normalized() {
    python3 - "$1" <<'PY'
import json, pathlib, sys
root = pathlib.Path(sys.argv[1])
for p in sorted(root.rglob("*.json")):
    v = json.loads(p.read_text())
    v.get("quadrature", {}).pop("method", None)
    v.pop("sidecar_digest", None)
    print(p.relative_to(root), json.dumps(v, sort_keys=True))
PY
}
files=$(digests "$scratch/b" | wc -l)
textures_a=$(digests "$scratch/a" | grep -v '\.json$' || true)
textures_b=$(digests "$scratch/b" | grep -v '\.json$' || true)
if ! diff <(echo "$textures_a") <(echo "$textures_b"); then
    echo "outputs differ (above: < $rev, > working tree)" >&2
    exit 1
fi
if ! diff <(normalized "$scratch/a") <(normalized "$scratch/b") >/dev/null; then
    diff <(normalized "$scratch/a") <(normalized "$scratch/b") | cut -c1-300
    echo "sidecars differ beyond quadrature.method (above: < $rev, > working tree)" >&2
    exit 1
fi
same=$(diff <(digests "$scratch/a") <(digests "$scratch/b") | grep -c '^>' || true)
echo "identical: $files files of $rev and the working tree ($same sidecar(s) differ only in quadrature.method)" >&2

#!/usr/bin/env bash
# The conformance suite against Mesa's software OpenGL (issue 12), in one command:
# installs Mesa (libosmesa6) and the Python packages if they are missing, writes
# the scenes, renders them with fixshade and with Mesa, compares them and checks
# the targets. Extra arguments go to compare.py (e.g. --png for side-by-side
# images in target/conformance/png/). See conformance/README.md.
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${CONFORMANCE_OUT:-target/conformance}
start=$(date +%s)
png=()
for a in "$@"; do [ "$a" = --png ] && png=(--png); done

echo "== Mesa (libosmesa6) and the Python packages"
if ! dpkg-query -W -f='${Status}' libosmesa6 2>/dev/null | grep -q "ok installed"; then
    sudo=()
    [ "$(id -u)" -ne 0 ] && sudo=(sudo)
    "${sudo[@]}" apt-get update -qq
    DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq libosmesa6 >/dev/null
fi
python3 -m pip install --quiet --disable-pip-version-check --root-user-action=ignore -r conformance/requirements.txt

echo "== scenes"
python3 conformance/scenes.py --out "$OUT/scenes"

echo "== fixshade (conformance/src/main.rs)"
# the test profile (opt-level 2) shares its dependencies with `cargo test`
cargo run --quiet --profile test -p fixshade-conformance -- --scenes "$OUT/scenes" --out "$OUT"

echo "== Mesa (llvmpipe through OSMesa)"
# the per-pixel shader's lighting function, evaluated per vertex, against fixed function
python3 conformance/mesa_render.py --scenes "$OUT/scenes" --out "$OUT" --selftest | tail -1
python3 conformance/mesa_render.py --scenes "$OUT/scenes" --out "$OUT" "${png[@]}"

echo "== compare"
python3 conformance/compare.py --scenes "$OUT/scenes" --out "$OUT" --check "$@"
echo "conformance suite: $(($(date +%s) - start)) s"

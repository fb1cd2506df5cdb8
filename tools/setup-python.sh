#!/usr/bin/env bash
# Creates the project's Python environment: a venv under target/ with the reference MCAP reader of the recording
# checks (the `mcap` package, independent of our Rust writer) and its protobuf decoder, and polars for the export
# example (docs/export.md). Idempotent: the packages are
# installed only when the venv is new or this script's requirements changed. Prints the venv's python on stdout.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
target="${CARGO_TARGET_DIR:-$repo/target}"
venv="$target/python-venv"
requirements="mcap>=1.2,<2 mcap-protobuf-support>=0.5,<1 protobuf>=4.25,<7 polars>=1.0,<2"
stamp="$venv/.gc2d-requirements"

python="${PYTHON:-python3}"
if ! command -v "$python" >/dev/null 2>&1; then
    echo "setup-python.sh: $python not found" >&2
    exit 2
fi

# Several test processes may ask at once on a fresh machine: one installs while the others wait for it.
mkdir -p "$target"
exec 9>"$target/python-venv.lock"
flock 9

if [[ ! -x "$venv/bin/python" ]]; then
    "$python" -m venv "$venv" >&2
fi
if [[ ! -f "$stamp" || "$(cat "$stamp")" != "$requirements" ]]; then
    # shellcheck disable=SC2086  # the requirement list is split into words on purpose
    "$venv/bin/python" -m pip install --quiet --disable-pip-version-check $requirements >&2
    echo "$requirements" > "$stamp"
fi
echo "$venv/bin/python"

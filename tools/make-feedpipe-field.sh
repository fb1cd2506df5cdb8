#!/usr/bin/env bash
# Regenerates scenes/fields/feedpipe_riser.vtk, the air in scenes/feedpipe_cfd.ron's riser, with OpenFOAM: copies the
# case tools/openfoam/feedpipe_riser to a temporary folder, meshes it (blockMesh), solves the steady turbulent flow
# (simpleFoam, k-epsilon), and exports the last time's velocity as legacy ASCII VTK (foamToVTK -legacy -ascii).
# Installs Debian's `openfoam` package when the solver is missing (needs root or sudo). Provenance:
# scenes/fields/README.md. Usage: tools/make-feedpipe-field.sh [OUTPUT.vtk]
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
case_dir="$repo/tools/openfoam/feedpipe_riser"
output="${1:-$repo/scenes/fields/feedpipe_riser.vtk}"

if ! command -v simpleFoam >/dev/null 2>&1; then
    echo "make-feedpipe-field.sh: OpenFOAM not found; installing Debian's openfoam package" >&2
    if [[ $(id -u) -eq 0 ]]; then sudo=(); elif command -v sudo >/dev/null 2>&1; then sudo=(sudo); else
        echo "make-feedpipe-field.sh: cannot install openfoam: not root and no sudo; install it with apt-get install openfoam" >&2
        exit 2
    fi
    "${sudo[@]}" apt-get update -qq >&2
    DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq openfoam >&2
fi

# Debian's package finds its etc/ (controlDict, cell models) through WM_PROJECT_DIR, which its bashrc would set.
if [[ -z "${WM_PROJECT_DIR:-}" && -d /usr/share/openfoam/etc ]]; then
    export WM_PROJECT_DIR=/usr/share/openfoam
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cp -r "$case_dir" "$work/case"
cd "$work/case"
echo "make-feedpipe-field.sh: meshing and solving in $work/case (logs there)" >&2
blockMesh > log.blockMesh 2>&1 || { tail -20 log.blockMesh >&2; exit 1; }
if ! simpleFoam > log.simpleFoam 2>&1; then
    tail -20 log.simpleFoam >&2
    exit 1
fi
grep -E "^(SIMPLE solution converged|End)" log.simpleFoam >&2 || true
# Only the velocity of the last time written; -nearCellValue would put cell values on the walls' points, while the
# default interpolates the points from the cells and the boundary values (zero on the walls).
foamToVTK -latestTime -legacy -ascii -fields '(U)' -noFaceZones -noLagrangian > log.foamToVTK 2>&1 \
    || { tail -20 log.foamToVTK >&2; exit 1; }
vtk="$(find VTK -maxdepth 1 -name '*.vtk' | sort | tail -1)"
if [[ -z "$vtk" ]]; then
    echo "make-feedpipe-field.sh: foamToVTK wrote no .vtk file" >&2
    exit 1
fi
mkdir -p "$(dirname "$output")"
cp "$vtk" "$output"
echo "make-feedpipe-field.sh: wrote $output ($(wc -c < "$output") bytes)" >&2

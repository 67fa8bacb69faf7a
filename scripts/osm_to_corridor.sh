#!/usr/bin/env bash
# From an OpenStreetMap extract to a platoonsim corridor (docs/import.md, "From OpenStreetMap"):
# SUMO's netconvert turns the motorway of the extract into a SUMO network, with the options SUMO
# documents for freeways, and `platoonsim import sumo` turns that into a scenario file.
#
#   scripts/osm_to_corridor.sh EXTRACT.osm SCENARIO.toml [IMPORT OPTIONS...]
#
# IMPORT OPTIONS go to `platoonsim import sumo` as they are (--routes, --additional,
# --mainline, --edge-detectors, --interval-s, --duration-s). The SUMO network is kept next to
# the scenario as SCENARIO.net.xml (for routes, SUMO runs and --mainline edge ids).
#
# netconvert: $NETCONVERT, else `netconvert` on the PATH, else the `eclipse-sumo` Python
# package's (python3 -m pip install eclipse-sumo). platoonsim: $PLATOONSIM, else `platoonsim`
# on the PATH, else target/release/platoonsim of this repository.
# Extra netconvert options: $NETCONVERT_OPTIONS (split on spaces), e.g. "--ramps.ramp-length 200".
set -euo pipefail

usage() {
    echo "usage: $0 EXTRACT.osm SCENARIO.toml [platoonsim import sumo options...]" >&2
    exit 2
}
[ $# -ge 2 ] || usage
osm=$1
scenario=$2
shift 2
if [ ! -f "$osm" ]; then
    echo "error: $osm: no such OpenStreetMap file" >&2
    exit 1
fi
case "$scenario" in
*.toml) ;;
*)
    echo "error: $scenario: the scenario file must end in .toml" >&2
    exit 1
    ;;
esac

find_netconvert() {
    if [ -n "${NETCONVERT:-}" ]; then
        echo "$NETCONVERT"
    elif command -v netconvert >/dev/null 2>&1; then
        echo netconvert
    else
        local home
        home=$(python3 -c "import sumo; print(sumo.SUMO_HOME)" 2>/dev/null) || return 1
        [ -x "$home/bin/netconvert" ] || return 1
        echo "$home/bin/netconvert"
    fi
}
if ! netconvert=$(find_netconvert); then
    echo "error: SUMO's netconvert not found: set NETCONVERT, put netconvert on the PATH, or" \
        "python3 -m pip install eclipse-sumo" >&2
    exit 1
fi
if [ -n "${PLATOONSIM:-}" ]; then
    platoonsim=$PLATOONSIM
elif command -v platoonsim >/dev/null 2>&1; then
    platoonsim=platoonsim
else
    platoonsim="$(cd "$(dirname "$0")/.." && pwd)/target/release/platoonsim"
    if [ ! -x "$platoonsim" ]; then
        echo "error: platoonsim not found: set PLATOONSIM, put it on the PATH, or" \
            "cargo build --release" >&2
        exit 1
    fi
fi

net="${scenario%.toml}.net.xml"
mkdir -p "$(dirname "$scenario")"
# The options, and why (docs/import.md):
#   --keep-edges.by-type …      only the motorway and trunk roads and their ramps (links): the
#                               corridor, not the town around it
#   --remove-edges.isolated     drops pieces of road that the type filter cut loose
#   --ramps.guess               SUMO's freeway ramps: on-ramps get an acceleration lane and
#                               off-ramps a deceleration lane (edges …-AddedOnRampEdge /
#                               …-AddedOffRampEdge), which the importer reads as such
#   --geometry.remove           joins the many short OSM ways of one road into one edge
#   --junctions.join            joins the cluster of nodes where ramps meet into one junction
#   --no-turnarounds            no U-turns onto the other carriageway at the ends
#   --output.street-names       keeps the ways' names: they become the ramps' names
# shellcheck disable=SC2086
"$netconvert" --osm-files "$osm" \
    --keep-edges.by-type highway.motorway,highway.motorway_link,highway.trunk,highway.trunk_link \
    --remove-edges.isolated \
    --ramps.guess --geometry.remove --junctions.join \
    --no-turnarounds --output.street-names \
    ${NETCONVERT_OPTIONS:-} \
    --output-file "$net"
"$platoonsim" import sumo "$net" "$@" --out "$scenario"

#!/bin/bash
# Whether two kepler binaries give the same bytes: the default drawing's JSON and SVG and the
# SVG of `--edges all --hidden`, for every mesh in MODELS, on 1 and 2 threads.
#
#     bench/peers/same.sh A B [MODELS]
#
# Prints each file that differs, then "same N differ M"; exits 1 when any differs.
set -u
A=$1 B=$2 M=${3:-../shared/models}
D=$(mktemp -d)
trap 'rm -rf "$D"' EXIT
same=0 differ=0
for m in "$M"/*.obj; do
    n=$(basename "$m" .obj)
    for t in 1 2; do
        for k in A B; do
            bin=${!k}
            RAYON_NUM_THREADS=$t "$bin" render -q "$m" --dir -1,-2,-3 \
                --json "$D/$n.$t.$k.json" --svg "$D/$n.$t.$k.svg"
            RAYON_NUM_THREADS=$t "$bin" render -q "$m" --dir -1,-2,-3 \
                --edges all --hidden --svg "$D/$n.$t.$k.hidden.svg"
        done
        for s in json svg hidden.svg; do
            if cmp -s "$D/$n.$t.A.$s" "$D/$n.$t.B.$s"; then
                same=$((same + 1))
            else
                differ=$((differ + 1))
                echo "differs: $n, $t threads, $s"
            fi
        done
    done
done
echo "same $same differ $differ"
[ "$differ" -eq 0 ]

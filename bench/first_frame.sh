#!/bin/sh
# First-frame dcs timings: a fresh `penumbra render` per run (a light's first frame), 3 runs per
# configuration, after one untimed run that warms Mesa's shader cache. Usage: [NS="16 64"] sh bench/first_frame.sh PENUMBRA OUTDIR (256^2; NS: sample counts)
P="$1"; O="$2"; mkdir -p "$O"
for sc in default scenes/engine.json scenes/bunny-crowd.json; do
  name=$(basename "$sc" .json); arg="$sc"; [ "$sc" = default ] && arg=""
  for n in ${NS:-16 64}; do
    $P render $arg -t dcs -W 256 -H 256 --samples $n --json -o /tmp/ff-warm.png >/dev/null 2>&1
    for i in 1 2 3; do
      $P render $arg -t dcs -W 256 -H 256 --samples $n --json -o /tmp/ff-$name.png > "$O/$name-$n-$i.json" 2>/dev/null
    done
  done
done

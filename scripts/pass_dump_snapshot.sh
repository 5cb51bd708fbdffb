#!/usr/bin/env bash
# Renders every technique with --dump-passes into OUTDIR (image, mask, every pass buffer and
# passes.json), on two scenes and the footprint/variant settings that change a technique's pass
# list. scripts/compare_pass_dumps.py compares two such snapshots (a restructuring must leave
# every image, mask and passes.json bit-identical).
#   usage: scripts/pass_dump_snapshot.sh OUTDIR [SHADOWLAB]
set -euo pipefail
out=${1:?usage: pass_dump_snapshot.sh OUTDIR [SHADOWLAB]}
bin=${2:-build/bin/shadowlab}
mkdir -p "$out"
techniques=$("$bin" list | awk '/^techniques:/{on=1;next} /^[a-z]+:$/{on=0} on && /^  [a-z]+\.[a-z0-9-]+ /{print $1}')
variants() {  # technique -> one line of extra options per variant
  case $1 in
    legacy.pcf|modern.pcf) printf '%s\n' "--filter 2" "--filter 3" "--filter 4" ;;
    legacy.fast-pcf|modern.fast-pcf) printf '%s\n' "--filter 2" "--filter 4" ;;
    legacy.ramp|modern.ramp) printf '%s\n' "" "--precision 12" ;;
    modern.hybrid) printf '%s\n' "" "--param mask=tiles" ;;
    modern.gems16) printf '%s\n' "" "--param kernel=bicubic" ;;
    reference.hard) printf '%s\n' "" "--param pixel=area --param pixel-samples=2" ;;
    reference.soft) printf '%s\n' "--param rays=16" ;;
    *) printf '%s\n' "" ;;
  esac
}
for t in $techniques; do
  for s in brabec fence; do
    i=0
    while IFS= read -r v; do
      d="$out/$t/$s/$i"; mkdir -p "$d"
      map="--shadow-map 256"
      case $t in modern.volumes|reference.*) map="" ;; esac
      # shellcheck disable=SC2086
      "$bin" render --scene "$s" --technique "$t" --size 200x150 $map $v \
        --out "$d/image.png" --mask "$d/mask.png" --dump-passes "$d/passes" \
        >"$d/stdout.json" 2>"$d/stderr.txt" || echo "exit $? from $t $s $v (see $d/stderr.txt)"
      i=$((i + 1))
    done < <(variants "$t")
  done
done
echo "snapshot in $out"

#!/usr/bin/env bash
# What the refinement to a local minimum adds to the automatic singularity placement, over CGAL's data set:
# for each mesh and N, our program with the smoothest field's singularities (--auto --no-refine) and with them
# refined (--auto, which refines by default since these numbers; the same as --auto --refine --cancel-pairs):
# singularities, energy and times of both, the numbers behind the manual's "Refined by default".
#
#   bash scripts/refinement_table.sh [PROGRAM] [MESH.off ...]
#
# PROGRAM: our command-line program built Release (default /tmp/b2/trivial_connections). It is copied into the
# output directory first (after waiting for it to exist and not to have changed for a few seconds), so that a
# rebuild during the run neither makes it vanish nor mixes two versions in one table.
# MESH: default every *.off of .cgal-data/data/meshes (scripts/fetch_cgal_data.sh).
# The two command lines are PROGRAM MESH --n N $TC_SMOOTHEST (default "--auto --no-refine") and PROGRAM MESH --n N
# $TC_REFINED (default "--auto"; a program older than --no-refine needs TC_SMOOTHEST=--auto
# TC_REFINED="--auto --refine --cancel-pairs"), both with --progress and with --connection, --field
# in the output directory, for N in TC_TABLE_N (default 4; e.g. TC_TABLE_N="1 2"). Each run once (no median),
# timed whole by /usr/bin/time (wall seconds, maximum resident size), stopped after TC_TABLE_TIMEOUT seconds
# (default 120). Outputs and logs go to TC_TABLE_DIR (default a new directory /tmp/refinement_table.XXXXXX,
# kept; its path is printed at the end).
# Parsed from the runs: stdout's 'mesh:' line (faces), 'component i: ... genus g, b boundary loops' lines, the
# last 'energy: X', the singularity count ('singularities: S' if printed, else the 'refinement: ... S0 -> S1
# singularities' or 'placement: ...; S singularities' line), whether the refinement line says 'a local
# minimum'; the placement time of the smoothest run from its 'time:' line (ms; it would include the refinement
# in the refined run); from the refined run's --progress lines on stderr ('[ t s] placement ... done ( x s; ...)'
# and '[ t s] refinement ... done ( y s; ...)', 10 ms resolution) the refinement time and the ratio
# refinement / placement of that same run ('-' when both show 0.00 s; '> r' with the placement taken as
# 0.005 s when only it shows 0.00 s).
# Meshes the program rejects (exit status 1 in both runs with the same message: non-manifold, not triangles,
# no vertex, ...) are left out of the table and listed at the end with the program's one-line error; other
# failures (a timeout, a crash, only one run failing) keep their row and are listed too.
# Prints a Markdown table, then a summary. Timings are of single runs on a machine possibly busy with other
# work: noisy, especially below 0.1 s.
set -euo pipefail
program=${1:-/tmp/b2/trivial_connections}
[ $# -gt 0 ] && shift
here=$(cd "$(dirname "$0")/.." && pwd)
data="$here/.cgal-data/data/meshes"
meshes=("$@")
if [ ${#meshes[@]} -eq 0 ]; then
  shopt -s nullglob
  meshes=("$data"/*.off)
  shopt -u nullglob
fi
[ ${#meshes[@]} -gt 0 ] || { echo "no mesh (default: $data/*.off; scripts/fetch_cgal_data.sh)" >&2; exit 2; }
read -r -a smoothest <<< "${TC_SMOOTHEST:---auto --no-refine}"
read -r -a refined <<< "${TC_REFINED:---auto}"
limit=${TC_TABLE_TIMEOUT:-120}
out=${TC_TABLE_DIR:-$(mktemp -d /tmp/refinement_table.XXXXXX)}
mkdir -p "$out"
out=$(cd "$out" && pwd)
case "$out/" in "$here"/*) echo "TC_TABLE_DIR must be outside the repository ($here)" >&2; exit 2 ;; esac

# the program, copied once it exists and has not changed for 5 s (another build may be writing it)
for _ in $(seq 120); do
  if [ -x "$program" ] && [ $(( $(date +%s) - $(stat -c %Y "$program") )) -ge 5 ]; then break; fi
  sleep 5
done
[ -x "$program" ] || { echo "no program at $program" >&2; exit 2; }
cp "$program" "$out/trivial_connections"
prog="$out/trivial_connections"
version=$("$prog" --version 2>&1 | head -1 || true)

run() { # TAG ARGS...: runs the program (--progress) under timeout and /usr/bin/time; stdout to TAG.out, stderr
        # to TAG.err; prints "status seconds peak_MB"
  local tag=$1; shift
  local status=0
  /usr/bin/time -f '%e %M' -o "$tag.time" timeout "$limit" "$prog" "$@" --progress \
    --connection "$out/connection.txt" --field "$out/field.txt" > "$tag.out" 2> "$tag.err" || status=$?
  tail -1 "$tag.time" | awk -v s="$status" '{printf "%d %.2f %.0f\n", s, $1, $2 / 1024}'
}
energy() { grep -o '^energy: [-+0-9.eE]*' "$1" | tail -1 | awk '{print $2}' || true; }
count() { # TAG.out: the number of singularities used
  local s
  s=$(grep -o '^singularities: [0-9]*' "$1" | tail -1 | awk '{print $2}' || true)
  [ -n "$s" ] || s=$(grep '^refinement:' "$1" | grep -o '[0-9]* singularities' | tail -1 | awk '{print $1}' || true)
  [ -n "$s" ] || s=$(grep '^placement:' "$1" | grep -o '[0-9]* singularities' | tail -1 | awk '{print $1}' || true)
  echo "${s:-?}"
}
phase() { # TAG.err PHASE: the seconds of a --progress phase ('PHASE ... done ( x s' or 'PHASE done ( x s')
  sed -n "s/.*] $2\( \.\.\.\)\{0,1\} done ( *\([0-9.]*\) s.*/\2/p" "$1" | tail -1
}
placement_time() { grep -o 'placement [0-9.]* s' "$1" | tail -1 | awk '{print $2}' || true; }
why() { # TAG STATUS: the program's one-line error (the last stderr line that is not a --progress line, without
          # the program's name and the mesh's path), else why not
  local tag=$1 status=$2 line
  line=$(grep -v '^\[' "$tag.err" | grep -v '^ *$' | tail -1 | tr '|' '/' || true)
  line=${line#trivial_connections: }
  line=${line//"$mesh: "/}
  line=${line:0:160}
  if [ "$status" -eq 124 ]; then line="timeout after $limit s"
  elif [ "$status" -gt 128 ]; then line="killed by signal $((status - 128))${line:+: $line}"
  fi
  echo "${line:-exit status $status}"
}
topology() { # TAG.out: per component 'genus g, b boundary loops' as g/b, joined by ' '; at most 4 listed, then
             # the number of components of the 'mesh:' line
  local k
  k=$(grep -o '^mesh: .* [0-9]* components*$' "$1" | head -1 | awk '{print $(NF-1)}' || true)
  grep -o 'genus [0-9]*, [0-9]* boundary loop' "$1" | awk -v k="${k:-0}" '{g = $2; sub(",", "", g); s[NR] = g "/" $3}
    END {for (i = 1; i <= NR && i <= 4; ++i) printf "%s%s", (i > 1 ? " " : ""), s[i];
         if (k > 4 || NR > 4) printf " ... (%d components)", (k > NR ? k : NR)}' || true
}

rows="$out/rows.tsv" # per row: name n energy_ratio time_ratio local_minimum placement_s refinement_s whole_s whole_r
                    # energy_s energy_r placement_r stop (placement_s: 'time:' line of the smoothest run;
                    # refinement_s, placement_r: --progress lines of the refined run; stop: why the refinement ended)
: > "$rows"
rejected="$out/rejected.txt"; : > "$rejected"
failed="$out/failed.txt"; : > "$failed"
echo "Program: \`$version\` ($program); \`--n N ${smoothest[*]}\` against \`--n N ${refined[*]}\`; N in ${TC_TABLE_N:-4};" \
  "single runs, timeout $limit s; logs in $out."
echo
echo "| mesh | faces | genus/boundaries | N | smoothest: singularities | energy | placement s | whole run s | refined: singularities | energy | refinement s | whole run s | energy after / before | refinement / placement time | local minimum |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for mesh in "${meshes[@]}"; do
  name=$(basename "$mesh" .off)
  for n in ${TC_TABLE_N:-4}; do
    tag_s="$out/$name.n$n.smoothest"; tag_r="$out/$name.n$n.refined"
    read -r st_s t_s m_s <<< "$(run "$tag_s" "$mesh" --n "$n" "${smoothest[@]}")"
    read -r st_r t_r m_r <<< "$(run "$tag_r" "$mesh" --n "$n" "${refined[@]}")"
    if [ "$st_s" -eq 1 ] && [ "$st_r" -eq 1 ] && [ "$(why "$tag_s" 1)" = "$(why "$tag_r" 1)" ]; then
      awk -v m="$name: " 'index($0, m) == 1 {found = 1} END {exit !found}' "$rejected" ||
        echo "$name: $(why "$tag_s" 1)" >> "$rejected"
      continue
    fi
    src="$tag_s.out"; [ "$st_s" -eq 0 ] || src="$tag_r.out"
    faces=$(grep -o '^mesh: .* [0-9]* faces' "$src" | head -1 | awk '{print $(NF-1)}' || true)
    topo=$(topology "$src")
    # the smoothest field's singularities
    e_s="-"; p_s="-"
    if [ "$st_s" -eq 0 ]; then
      s_cells="$(count "$tag_s.out") | $(energy "$tag_s.out") | $(placement_time "$tag_s.out") | $t_s"
      e_s=$(energy "$tag_s.out"); p_s=$(placement_time "$tag_s.out")
    else
      s_cells="failed: $(why "$tag_s" "$st_s") | - | - | $t_s"
      echo "$name (N = $n, smoothest): $(why "$tag_s" "$st_s")" >> "$failed"
    fi
    # refined
    e_r="-"; ref="-"; pl="-"; lm="-"; stop="-"
    if [ "$st_r" -eq 0 ]; then
      e_r=$(energy "$tag_r.out"); ref=$(phase "$tag_r.err" refinement); pl=$(phase "$tag_r.err" placement)
      r_cells="$(count "$tag_r.out") | $e_r | ${ref:--} | $t_r"
      if grep '^refinement:' "$tag_r.out" | grep -q 'a local minimum'; then lm=yes; else lm=no; fi
      stop=$(grep '^refinement:' "$tag_r.out" | tail -1 | sed -n 's/.* trial solves (\(.*\))$/\1/p' || true)
    else
      r_cells="failed: $(why "$tag_r" "$st_r") | - | - | $t_r"
      echo "$name (N = $n, refined): $(why "$tag_r" "$st_r")" >> "$failed"
    fi
    e_ratio=$(awk -v a="$e_r" -v b="$e_s" 'BEGIN {
      if (a == "-" || b == "-" || a == "" || b == "") print "-"
      else if (b + 0 == 0) print (a + 0 == 0 ? "1" : "-")
      else printf "%.4f", a / b }')
    t_ratio=$(awk -v r="${ref:--}" -v p="${pl:--}" 'BEGIN {
      if (r == "-" || p == "-" || r == "" || p == "") print "-"
      else if (p + 0 >= 0.01) printf "%.2f", r / p
      else if (r + 0 >= 0.01) printf "> %.1f", r / 0.005
      else print "-" }')
    echo "| $name | ${faces:-?} | ${topo:--} | $n | $s_cells | $r_cells | $e_ratio | $t_ratio | $lm |"
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$n" "$e_ratio" "$t_ratio" "$lm" "$p_s" \
      "${ref:--}" "$t_s" "$t_r" "$e_s" "$e_r" "${pl:--}" "${stop:--}" >> "$rows"
  done
done

# summary
median() { sort -g | awk '{v[NR] = $1} END {if (NR == 0) print "-"; else if (NR % 2) print v[(NR + 1) / 2];
                                            else printf "%.4g\n", (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
echo
echo "Summary ($(date -u +%Y-%m-%d), N in ${TC_TABLE_N:-4}; single runs, timings noisy):"
echo
meshes_in=$(cut -f1 "$rows" | sort -u | wc -l)
echo "- meshes in the table: $meshes_in ($(wc -l < "$rows") rows); rejected by the program: $(wc -l < "$rejected"); other failures: $(wc -l < "$failed")"
e_ok=$(awk -F'\t' '$3 != "-"' "$rows")
n_e=$(printf '%s' "$e_ok" | grep -c . || true)
lower=$(printf '%s' "$e_ok" | awk -F'\t' 'NF && $11 + 0 < $10 + 0' | wc -l)
same=$(printf '%s' "$e_ok" | awk -F'\t' 'NF && $11 + 0 == $10 + 0' | wc -l)
echo "- rows with both energies: $n_e; refined energy lower: $lower; equal: $same; higher: $((n_e - lower - same))"
if [ "$n_e" -gt 0 ]; then
  echo "- energy after / before: median $(printf '%s\n' "$e_ok" | cut -f3 | median)," \
    "min $(printf '%s\n' "$e_ok" | cut -f3 | sort -g | head -1), max $(printf '%s\n' "$e_ok" | cut -f3 | sort -g | tail -1)"
fi
t_ok=$(awk -F'\t' '$4 != "-" && $4 !~ />/ {print $4}' "$rows")
n_gt=$(awk -F'\t' '$4 ~ />/' "$rows" | wc -l)
if [ -n "$t_ok" ]; then
  echo "- refinement / placement time (rows with placement >= 0.01 s: $(printf '%s\n' "$t_ok" | wc -l)): median" \
    "$(printf '%s\n' "$t_ok" | median), max $(printf '%s\n' "$t_ok" | sort -g | tail -1);" \
    "rows above 1: $(printf '%s\n' "$t_ok" | awk '$1 > 1' | wc -l); rows with placement 0.00 s and refinement >= 0.01 s: $n_gt"
fi
echo "- local minimum reached: $(awk -F'\t' '$5 == "yes"' "$rows" | wc -l) of $(awk -F'\t' '$5 != "-"' "$rows" | wc -l) refined runs"
awk -F'\t' '{if ($6 != "-") p += $6; if ($7 != "-") r += $7; s += $8; t += $9}
  END {printf "- total times: smoothest runs %.2f s (placement %.2f s); refined runs %.2f s (refinement %.2f s)\n", s, p, t, r}' "$rows"
listing() { # TITLE AWK_CONDITION: the rows that meet the condition, one line each
  local rows_met
  rows_met=$(awk -F'\t' "$2" "$rows")
  [ -n "$rows_met" ] || return 0
  echo
  echo "$1 ($(printf '%s\n' "$rows_met" | wc -l)):"
  echo
  printf '%s\n' "$rows_met" | awk -F'\t' '{printf "- %s, N = %s: energy %s -> %s (ratio %s); refined run: placement %s s, refinement %s s (ratio %s); stop: %s\n",
                                          $1, $2, $10, $11, $3, $12, $7, $4, $13}'
}
listing "Refined energy not lower" '$3 != "-" && $11 + 0 >= $10 + 0'
listing "No local minimum reached" '$5 == "no"'
listing "Refinement longer than the placement (refined run's --progress lines)" '$4 != "-" && ($4 ~ />/ || $4 + 0 > 1)'
if [ -s "$rejected" ]; then
  echo
  echo "Rejected by the program ($(wc -l < "$rejected")):"
  echo
  sed 's/^/- /' "$rejected"
fi
if [ -s "$failed" ]; then
  echo
  echo "Other failures ($(wc -l < "$failed")):"
  echo
  sed 's/^/- /' "$failed"
fi

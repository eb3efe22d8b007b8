#!/usr/bin/env bash
# The program's errors on bad --boundary-indices and --constraints files: exit status 1, a one-line message
# that names the problem, and no output file left behind. Used by ctest (CMakeLists.txt).
# Usage: cli_errors.sh PROGRAM OUT_DIR PIG_OFF SPHERE_OFF
set -uo pipefail
cli="$1" out="$2" pig="$3" sphere="$4"
mkdir -p "$out"
failures=0

# expect_with OPTION FILE_NAME MESH FILE_CONTENT N MESSAGE_PART [MORE OPTIONS...]
expect_with() {
  local option="$1" name="$2" mesh="$3" content="$4" n="$5" part="$6"
  shift 6
  local file="$out/$name" conn="$out/c.txt" field="$out/f.txt"
  printf '%b' "$content" > "$file"
  rm -f "$conn" "$field"
  local message status
  message=$("$cli" "$mesh" "$option" "$file" --n "$n" --connection "$conn" --field "$field" "$@" 2>&1 >/dev/null)
  status=$?
  if [ "$status" != 1 ]; then
    echo "FAIL ($part): exit status $status, expected 1"; failures=$((failures + 1))
  elif [[ "$message" != *"$part"* ]]; then
    echo "FAIL ($part): message was: $message"; failures=$((failures + 1))
  elif [ -e "$conn" ] || [ -e "$field" ]; then
    echo "FAIL ($part): an output file was left behind"; failures=$((failures + 1))
  else
    echo "ok: $message"
  fi
}
# expect MESH FILE_CONTENT N MESSAGE_PART: a --boundary-indices file
expect() { expect_with --boundary-indices boundary.idx "$@"; }
# expect_constraints MESH FILE_CONTENT N MESSAGE_PART [MORE OPTIONS...]: a --constraints file
expect_constraints() { expect_with --constraints constraints.txt "$@"; }

# pig.off: genus 0, 7 boundary loops (through vertices 4, 314, 408, 291, 463, 429, 352; vertex 1 is interior),
# chi = -5
expect "$pig" '1 1\n' 4 "is not on a boundary"                       # an interior vertex
expect "$pig" '4 -1\n0 -1\n' 4 "are on the same boundary loop"       # 0 and 4 are on the same (3-vertex) hole
expect "$pig" '4 1/8\n' 4 "is not a multiple of 1/4"
expect "$pig" '4 -1\n314 -1\n' 4 "boundary.idx: 2 of the 7 boundary loops of component 0 are prescribed"
expect "$pig" '4 -1\n314 -1\n408 -1\n291 -1\n463 -1\n429 -1\n352 -1\n' 1 "boundary.idx: Poincare-Hopf"   # sum -7, chi = -5
expect "$pig" '4 -1\n4 -1\n' 1 "twice"
expect "$pig" '99999 1\n' 1 "99999"                                   # out of range
# indices within Poincare-Hopf but beyond 2^10 turns: the rounding of 2 pi k would show in the residuals
expect "$pig" '4 1000000000\n314 -1000000000\n408 -1\n291 -1\n463 -1\n429 -1\n352 -1\n' 1 "is too large (at most 1024"
expect "$pig" '4 1025\n314 -1025\n408 -1\n291 -1\n463 -1\n429 -1\n352 -1\n' 1 "is too large (at most 1024"
expect "$pig" 'garbage\n' 1 "boundary.idx"
expect "$sphere" '0 1\n' 1 "is not on a boundary"                     # a closed mesh has no boundary loop

# --constraints (pig.off has 891 faces; face 0 is a boundary face, face 2 an interior one)
expect_constraints "$pig" '99999 1 0 0\n' 1 "constraints.txt:1: face 99999 does not exist"
expect_constraints "$pig" '-1 1 0 0\n' 1 "not a non-negative integer"
expect_constraints "$pig" '2 0 0 0\n' 1 "constraints.txt:1: face 2: the direction is the zero vector"
expect_constraints "$pig" '2 1 0\n' 1 "four fields"
expect_constraints "$pig" '2 nan 0 0\n' 1 "not a finite number"
expect_constraints "$pig" '2 1e999 0 0\n' 1 "not a finite number"
expect_constraints "$pig" '2 1 0 0\n# comment\n2 0 1 0\n' 1 "listed twice (lines 1 and 3)"
expect_constraints "$pig" '0 1 0 0\n' 4 "constraints.txt: face 0 is on the boundary" --align-boundary
expect_constraints "$out/missing.off" '2 1 0 0\n' 1 "missing.off"
# --guidance: the same format; a guided face on an aligned boundary, or also constrained
expect_with --guidance guides.txt "$pig" '0 1 0 0\n' 4 "guides.txt: face 0 is on the boundary" --align-boundary
expect_with --guidance guides.txt "$pig" '2 0 0 0\n' 4 "guides.txt:1: face 2: the direction is the zero vector"
printf '2 1 0 0\n' > "$out/both.txt"
expect_with --guidance guides.txt "$pig" '2 0 1 0\n' 4 "is in both" --constraints "$out/both.txt"
# a constraint file that cannot be read
rm -f "$out/c.txt" "$out/f.txt"
message=$("$cli" "$pig" --constraints "$out/no_such_file.txt" --connection "$out/c.txt" --field "$out/f.txt" 2>&1 >/dev/null)
status=$?
if [ "$status" != 1 ] || [[ "$message" != *"cannot read direction file"* ]] || [ -e "$out/c.txt" ]; then
  echo "FAIL (unreadable constraint file): status $status, message: $message"; failures=$((failures + 1))
else
  echo "ok: $message"
fi
# Under a limit on the address space (ulimit -v) the program finishes (it hung in OpenBLAS's threads before): with
# the field when the limit leaves it room (150 MB), and under a tighter one either so or with "out of memory" and
# no output file. Not with AddressSanitizer, which reserves terabytes of address space at start. (Below about
# 65 MB OpenBLAS cannot start its threads when it is loaded, before the program runs, and ends the process.)
# ldd's whole output is read first: with pipefail, "ldd | grep -q" fails when grep quits before ldd has written
# everything (SIGPIPE), which ran these checks under AddressSanitizer on a loaded machine.
libraries=$(ldd "$cli" 2>/dev/null || true)
if [[ "$libraries" != *libasan* ]]; then
  for kb in 150000 72000; do
    rm -f "$out/c.txt" "$out/f.txt"
    message=$(ulimit -v "$kb"; timeout 120 "$cli" "$pig" --auto --n 4 --connection "$out/c.txt" --field "$out/f.txt" 2>&1 >/dev/null)
    status=$?
    if [ "$status" = 0 ] && [ -s "$out/c.txt" ] && [ -s "$out/f.txt" ]; then
      echo "ok: ulimit -v $kb: the field"
    elif [ "$status" = 1 ] && [ "$kb" != 150000 ] && [[ "$message" == *"out of memory"* ]] && [ ! -e "$out/c.txt" ] && [ ! -e "$out/f.txt" ]; then
      echo "ok: ulimit -v $kb: $message"
    else
      echo "FAIL (ulimit -v $kb): exit status $status (124: hung), message: $message"; failures=$((failures + 1))
    fi
  done
fi
if [ "$failures" != 0 ]; then echo "$failures failure(s)"; exit 1; fi

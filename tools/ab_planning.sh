#!/usr/bin/env bash
# A/B timing of `SCurve::new` between two revisions of the crate (`.` for the working tree):
#
#   tools/ab_planning.sh A B [moves (100000)] [sweeps (10)]
#
# Both are linked into one binary (tools/ab_planning/) and each of the planning bench's random
# moves is timed with both, alternately, so that the machine's load falls on both alike. Two
# copies of the same code are laid out differently in one binary, and one may run 2–3 % faster
# for that alone; so the binary is built both ways round (A as `profilegen` and B as
# `profilegen_old`, then the other way), and the effect is the geometric mean of A/B from the two
# runs, the layout's share the other half. Prints both runs and the two figures.
set -euo pipefail
cd "$(dirname "$0")/.."
a=${1:?usage: tools/ab_planning.sh A B [moves] [sweeps]}
b=${2:?usage: tools/ab_planning.sh A B [moves] [sweeps]}
shift 2
root=target/ab-planning

# shellcheck source=tools/ab_planning/populate.sh
source tools/ab_planning/populate.sh

# Runs the binary with $1 as `profilegen` and $2 as `profilegen_old`; prints its line and
# leaves the ratio of means (the first over the second) in $ratio.
run() {
  populate "$1" "$root/a" profilegen
  populate "$2" "$root/b" profilegen_old
  cargo build --quiet --release --manifest-path tools/ab_planning/Cargo.toml
  local line
  line=$(tools/ab_planning/target/release/profilegen-ab-planning "$@")
  echo "$1 as new, $2 as old: $line"
  ratio=${line##* }
}

run "$a" "$b" "$@"
forward=$ratio
run "$b" "$a" "$@"
backward=$ratio
python3 -c "
import math
f, b = $forward, $backward
print(f'{\"$a\"} / {\"$b\"}: {math.sqrt(f / b):.4f} (time ratio; the layout alone: {math.sqrt(f * b):.4f})')
"

#!/usr/bin/env bash
# Checks that two revisions of the crate (`.` for the working tree) plan the same S-curve moves:
#
#   tools/ab_plans.sh A B [moves (100000)] [fractional moves (100000)]
#
# Both are linked into one binary (tools/ab_planning/, as tools/ab_planning.sh does for timing),
# which plans the planning bench's random moves with each and compares their plans, and steps
# moves of a few raw units of jerk from fractional positions with each, comparing every state.
# Prints the first few moves that differ; exit status 1 if any does. For a change meant to keep
# every plan (a faster search, a smaller table), the evidence that it did.
set -euo pipefail
cd "$(dirname "$0")/.."
a=${1:?usage: tools/ab_plans.sh A B [moves] [fractional moves]}
b=${2:?usage: tools/ab_plans.sh A B [moves] [fractional moves]}
shift 2
root=target/ab-planning

# shellcheck source=tools/ab_planning/populate.sh
source tools/ab_planning/populate.sh

populate "$a" "$root/a" profilegen
populate "$b" "$root/b" profilegen_old
cargo build --quiet --release --manifest-path tools/ab_planning/Cargo.toml
tools/ab_planning/target/release/profilegen-ab-planning --plans "$@"

#!/usr/bin/env bash
# The instruction counts of one cycle of every generator, by phase, on x86 and on a Cortex-M4
# (SPEC §16, issue #12):
#
#   tools/instruction_counts.sh            # both tables
#   tools/instruction_counts.sh --x86      # x86 only (callgrind)
#
# x86: benches/examples/step_instructions.rs steps each generator through a window of cycles that all
# lie in one phase of the bench move (benches/common), calling `step` through a trait object;
# callgrind counts the instructions inside `step` (callees included) and this divides by the
# window's cycles. Also x86 planning: benches/examples/plan_instructions.rs plans the planning
# bench's first 20,000 S-curve moves, and callgrind counts `SCurve::new` inclusive, per plan; then
# the same moves as re-plans (`--set-parameters`: `SCurve::set_parameters` on a generator at rest).
# Cortex-M4: tools/cortex_m4_budgets.sh (every cycle of every generator of the probe, counted
# under an emulator; the call itself included).
set -euo pipefail
cd "$(dirname "$0")/.."

cargo build --quiet --release -p profilegen-benches --example step_instructions
binary=target/release/examples/step_instructions
out="${TMPDIR:-/tmp}/profilegen-callgrind.$$"
trap 'rm -f "$out"' EXIT

echo "== x86 instructions per cycle (callgrind, inside the call; window of cycles of one phase)"
printf '%-26s %8s %8s %10s\n' window cycles instr/cycle function
"$binary" --list | while read -r name first last; do
  cycles=$((last - first + 1))
  case "$name" in
    microstep/*) function='profilegen::waveform::MicrostepTable::outputs' ;;
    velocity/*) function='<profilegen::velocity::VelocityContouring as profilegen::state::ProfileGenerator>::step' ;;
    trapezoidal/*) function='<profilegen::trapezoidal::Trapezoidal as profilegen::state::ProfileGenerator>::step' ;;
    scurve/*) function='<profilegen::scurve::SCurve as profilegen::state::ProfileGenerator>::step' ;;
    mcx514/*) function='<profilegen::mcx514::trapezoidal::Mcx514Trapezoidal as profilegen::state::ProfileGenerator>::step' ;;
    mcx514_scurve/*) function='<profilegen::mcx514::scurve::Mcx514SCurve as profilegen::state::ProfileGenerator>::step' ;;
    gearing/*) function='profilegen::gearing::ElectronicGear::follow' ;;
  esac
  valgrind --tool=callgrind --callgrind-out-file="$out" --collect-atstart=no \
    --toggle-collect='step_instructions::measure' --toggle-collect='step_instructions::outputs' \
    --toggle-collect='step_instructions::follow' \
    "$binary" "$name" >/dev/null 2>&1
  # Inclusive instructions of the function, over the window (collected only inside `measure`).
  total=$(callgrind_annotate --inclusive=yes "$out" 2>/dev/null \
    | grep -F ":$function [" | head -1 | awk '{gsub(",", "", $1); print $1}')
  if [ -z "$total" ]; then
    echo "$name: no count for $function" >&2
    exit 1
  fi
  awk -v n="$name" -v c="$cycles" -v t="$total" -v f="$function" \
    'BEGIN { printf "%-26s %8d %8.1f   %s\n", n, c, t / c, f }'
done

# Planning: SCurve::new over the first 20,000 moves of the planning bench, inclusive of all it
# calls (the moves' registers are drawn outside it), divided by the moves.
cargo build --quiet --release -p profilegen-benches --example plan_instructions
moves=20000
# The instructions callgrind counts inside function $1 (callees included) over the moves,
# planned by plan_instructions with the arguments that follow.
plan_count() {
  local function=$1
  shift
  valgrind --tool=callgrind --callgrind-out-file="$out" \
    target/release/examples/plan_instructions "$moves" "$@" >/dev/null 2>&1
  local count
  count=$(callgrind_annotate --inclusive=yes "$out" 2>/dev/null \
    | grep -F ":$function [" | head -1 | awk '{gsub(",", "", $1); print $1}')
  if [ -z "$count" ]; then
    echo "planning: no count for $function" >&2
    exit 1
  fi
  echo "$count"
}
function='profilegen::scurve::SCurve::new'
total=$(plan_count "$function")
# The same moves planned by `set_parameters` on a generator at rest (a re-plan).
replan_function='profilegen::scurve::SCurve::set_parameters'
replan=$(plan_count "$replan_function" --set-parameters)
echo
echo "== x86 instructions per S-curve plan (callgrind, inclusive; the planning bench's first moves)"
awk -v m="$moves" -v t="$total" -v f="$function" \
  'BEGIN { printf "%-26s %8d %8.0f   %s\n", "scurve/plan (mean)", m, t / m, f }'
awk -v m="$moves" -v t="$replan" -v f="$replan_function" \
  'BEGIN { printf "%-26s %8d %8.0f   %s\n", "scurve/replan (mean)", m, t / m, f }'

if [ "${1:-}" != "--x86" ]; then
  echo
  echo "== Cortex-M4 instructions per cycle (emulator, the call included)"
  tools/cortex_m4_budgets.sh --moves 200 "$@"
fi

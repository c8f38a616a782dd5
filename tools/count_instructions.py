#!/usr/bin/env python3
"""Counts the Cortex-M4 instructions that S-curve planning and stepping execute (SPEC §16).

Loads the probe image (probe/, `thumbv7em-none-eabihf`) into Unicorn as a Cortex-M4 and calls
its exported functions one at a time, like a C caller would: arguments in r0-r3, sp at the top
of RAM, lr a return address nothing else uses; the call ends when execution reaches that address.
Every instruction executed from the function's first to its return is counted, callees included
(soft-float `f64` routines, memcpy, ...).

Counting: a block hook adds the instruction count of each translated block executed, decoded
once per block with Capstone. `--verify` checks this against a hook on every instruction (exact,
slow) on a sample of calls, and checks the probe's own move generator against this one's calls.

Planning: moves 0 .. N-1 of benches/common/moves.rs (log-uniform over the whole register ranges),
each `probe_plan_bits(destination, velocity, acceleration, jerk)`: registers from bits,
`SCurve::new`, the generator kept. Stepping: `probe_step()` per cycle, one call per cycle, over
whole moves: a fixed moderate move and the random moves short enough to step to the end; each
cycle is classed ramp (phases I-III), cruise (IV), deceleration (V-VII) or rest (after the move).
Per-step counts include the call itself (entry, loading the static generator, return).

For the worst plan, the instructions are also attributed to the functions (symbols) they ran
in: the planner's own functions, and the library routines it calls (f64 arithmetic, 64-bit
division, memcpy).

Exit status: 0 when within the budgets given (none given: report only), 1 when a budget is
exceeded, 2 when the probe panicked, faulted or ran away, or on bad usage.
"""

from __future__ import annotations

import argparse
import bisect
import os
import random
import statistics
import struct
import sys
import time
from dataclasses import dataclass, field

from capstone import CS_ARCH_ARM, CS_MODE_MCLASS, CS_MODE_THUMB, Cs
from elftools.elf.elffile import ELFFile
from elftools.elf.sections import SymbolTableSection
from unicorn import (
    UC_ARCH_ARM,
    UC_HOOK_BLOCK,
    UC_HOOK_CODE,
    UC_MODE_MCLASS,
    UC_MODE_THUMB,
    UC_PROT_ALL,
    Uc,
    UcError,
)
from unicorn import arm_const as arm

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_ELF = os.path.join(ROOT, "probe", "target", "thumbv7em-none-eabihf", "release", "probe")

PAGE = 0x1000
# The return address given to every call: a mapped page that no code of the probe lives in,
# away from the 0xFxxxxxxx EXC_RETURN values a Cortex-M treats specially.
RETURN_PAGE = 0x0400_0000
# Words the harness passes out-pointers to (probe_move, probe_phases).
SCRATCH_PAGE = 0x0500_0000
STACK_PAINT = 0xA5

# The fixed moderate move that is stepped: 1,000,000 counts at 100 counts/cycle, acceleration
# 0.25 counts/cycle², jerk 0.01 counts/cycle³ (raw register bits).
FIXED_STEP_MOVE = (1_000_000, 100 << 16, 16_384, 42_949_673)


class ProbeFailure(Exception):
    """The probe panicked, faulted or ran away."""


def page_floor(address: int) -> int:
    return address & ~(PAGE - 1)


def page_ceil(address: int) -> int:
    return (address + PAGE - 1) & ~(PAGE - 1)


def describe_move(move: tuple[int, int, int, int]) -> str:
    destination, velocity, acceleration, jerk = move
    return (
        f"destination {destination} counts, velocity {velocity} ({velocity / 2**16:.6g} counts/cycle), "
        f"acceleration {acceleration} ({acceleration / 2**16:.6g} counts/cycle²), "
        f"jerk {jerk} ({jerk / 2**32:.6g} counts/cycle³)"
    )


@dataclass
class Call:
    """One call's result: r0/r1 as returned, and the instructions it executed."""

    r0: int
    r1: int
    instructions: int

    @property
    def u64(self) -> int:
        return self.r0 | (self.r1 << 32)


@dataclass
class Probe:
    path: str
    max_instructions: int
    symbols: dict[str, int] = field(default_factory=dict)
    functions: list[tuple[int, int, str]] = field(default_factory=list)

    def __post_init__(self) -> None:
        with open(self.path, "rb") as f:
            elf = ELFFile(f)
            if elf["e_machine"] != "EM_ARM":
                raise SystemExit(f"{self.path}: not an ARM image")
            segments = [
                (seg["p_paddr"], seg["p_vaddr"], seg.data(), seg["p_memsz"])
                for seg in elf.iter_segments()
                if seg["p_type"] == "PT_LOAD"
            ]
            for section in elf.iter_sections():
                if isinstance(section, SymbolTableSection):
                    for symbol in section.iter_symbols():
                        if symbol.name and symbol["st_info"]["type"] in ("STT_FUNC", "STT_OBJECT", "STT_NOTYPE"):
                            self.symbols[symbol.name] = symbol["st_value"]
                        if symbol["st_info"]["type"] == "STT_FUNC" and symbol["st_size"]:
                            start = symbol["st_value"] & ~1
                            self.functions.append((start, start + symbol["st_size"], demangle(symbol.name)))
        self.functions.sort()
        for name in ("probe_plan_bits", "probe_plan", "probe_move", "probe_step_setup", "probe_phases",
                     "probe_step", "probe_panicked", "_stack_top", "_stack_bottom"):
            if name not in self.symbols:
                raise SystemExit(f"{self.path}: no symbol {name} (is it the probe image?)")

        self.uc = Uc(UC_ARCH_ARM, UC_MODE_THUMB | UC_MODE_MCLASS)
        self.uc.ctl_set_cpu_model(arm.UC_CPU_ARM_CORTEX_M4)
        # Map every page a segment touches (flash image at its load address, RAM at its run
        # address), the RAM up to the stack top, the return page and the scratch page.
        regions: list[tuple[int, int]] = []
        for paddr, vaddr, _, memsz in segments:
            for base in {paddr, vaddr}:
                regions.append((page_floor(base), page_ceil(base + max(memsz, 1))))
        ram_base = page_floor(self.symbols["_stack_bottom"])
        self.stack_top = self.symbols["_stack_top"]
        regions.append((ram_base, page_ceil(self.stack_top)))
        regions += [(RETURN_PAGE, RETURN_PAGE + PAGE), (SCRATCH_PAGE, SCRATCH_PAGE + PAGE)]
        for start, end in merge(regions):
            self.uc.mem_map(start, end - start, UC_PROT_ALL)
        # The return page holds `udf` only: nothing may execute there (emulation stops on arrival).
        self.uc.mem_write(RETURN_PAGE, b"\x00\xde" * (PAGE // 2))
        # Flash image (load addresses), then initialized data copied to its run address and .bss
        # zeroed, as a reset handler would.
        for paddr, vaddr, data, memsz in segments:
            self.uc.mem_write(paddr, data)
            if vaddr != paddr:
                self.uc.mem_write(vaddr, data)
            if memsz > len(data):
                self.uc.mem_write(vaddr + len(data), bytes(memsz - len(data)))
        self.stack_bottom = self.symbols["_stack_bottom"]
        self.paint_stack()

        self.disassembler = Cs(CS_ARCH_ARM, CS_MODE_THUMB | CS_MODE_MCLASS)
        self.block_counts: dict[int, int] = {}
        self.count = 0
        self.exact = False
        self.raw_count = 0
        self.it_blocks: dict[int, tuple[int, int]] = {}
        self.it_start = self.it_end = 0
        self.failure: str | None = None
        self.profile: dict[int, int] | None = None
        self.uc.hook_add(UC_HOOK_BLOCK, self._on_block)
        panicked = self.symbols["probe_panicked"] & ~1
        self.uc.hook_add(UC_HOOK_CODE, self._on_panic, begin=panicked, end=panicked)

    # Hooks -------------------------------------------------------------------------------------

    def _on_block(self, uc: Uc, address: int, size: int, _data: object) -> None:
        key = (address << 16) | size
        n = self.block_counts.get(key)
        if n is None:
            n = self.block_counts[key] = self._decode(address, size)
        if not self.exact:
            self.count += n
        if self.profile is not None:
            self.profile[address] = self.profile.get(address, 0) + n
        if self.count > self.max_instructions:
            self.failure = f"ran away: more than {self.max_instructions} instructions"
            uc.emu_stop()

    def _on_instruction(self, uc: Uc, address: int, size: int, _data: object) -> None:
        # Unicorn runs the hook of an instruction inside an IT block only when its condition
        # passes, but the Cortex-M4 issues every instruction of the block (one that fails its
        # condition executes as a NOP, in a cycle): so an IT counts itself and its whole block,
        # and the hooks that fire inside the block are not counted again.
        if self.it_start <= address < self.it_end:
            self.raw_count += 1
            return
        it = self.it_blocks.get(address)
        if it is None:
            it = self.it_blocks[address] = self._it_block(address)
        self.count += 1 + it[0]
        self.raw_count += 1
        if it[0]:
            self.it_start, self.it_end = address + size, it[1]

    def _it_block(self, address: int) -> tuple[int, int]:
        """(the number of instructions in the IT block that the instruction at `address` starts,
        the address after the block); (0, 0) when it is not an IT."""
        code = bytes(self.uc.mem_read(address, 2 + 4 * 4))
        instructions = list(self.disassembler.disasm_lite(code, address, 5))
        mnemonic = instructions[0][2]
        if not mnemonic.startswith("it"):
            return (0, 0)
        k = len(mnemonic) - 1
        last = instructions[k]
        return (k, last[0] + last[1])

    def _on_panic(self, uc: Uc, address: int, size: int, _data: object) -> None:
        line = self.read_u32(self.symbols["PROBE_PANIC_LINE"]) if "PROBE_PANIC_LINE" in self.symbols else 0
        where = ""
        if line:
            file_at = self.read_u32(self.symbols["PROBE_PANIC_FILE"])
            length = self.read_u32(self.symbols["PROBE_PANIC_FILE_LEN"])
            name = bytes(uc.mem_read(file_at, min(length, 512))).decode("utf-8", "replace")
            where = f" at {name}:{line}"
        self.failure = f"panicked{where}"
        uc.emu_stop()

    def _decode(self, address: int, size: int) -> int:
        code = bytes(self.uc.mem_read(address, size))
        n = 0
        end = address
        for insn_address, insn_size, _, _ in self.disassembler.disasm_lite(code, address):
            n += 1
            end = insn_address + insn_size
        if end != address + size:
            raise ProbeFailure(f"cannot decode the block at {address:#x} (+{size}) past {end:#x}")
        return n

    # Calls -------------------------------------------------------------------------------------

    def read_u32(self, address: int) -> int:
        return struct.unpack("<I", self.uc.mem_read(address, 4))[0]

    def read_words(self, address: int, n: int) -> list[int]:
        return list(struct.unpack(f"<{n}I", self.uc.mem_read(address, 4 * n)))

    def call(self, name: str, *args: int) -> Call:
        if len(args) > 4:
            raise ValueError("at most 4 register arguments")
        uc = self.uc
        for register, value in zip((arm.UC_ARM_REG_R0, arm.UC_ARM_REG_R1, arm.UC_ARM_REG_R2,
                                    arm.UC_ARM_REG_R3), args):
            uc.reg_write(register, value & 0xFFFF_FFFF)
        uc.reg_write(arm.UC_ARM_REG_SP, self.stack_top)
        uc.reg_write(arm.UC_ARM_REG_LR, RETURN_PAGE | 1)
        self.count = 0
        self.failure = None
        try:
            uc.emu_start(self.symbols[name] | 1, RETURN_PAGE)
        except UcError as error:
            pc = uc.reg_read(arm.UC_ARM_REG_PC)
            raise ProbeFailure(f"{name}{args}: {error} at pc {pc:#x}") from None
        if self.failure:
            raise ProbeFailure(f"{name}{args}: {self.failure}")
        pc = uc.reg_read(arm.UC_ARM_REG_PC)
        if pc & ~1 != RETURN_PAGE:
            raise ProbeFailure(f"{name}{args}: stopped at pc {pc:#x}, not at the return address")
        return Call(uc.reg_read(arm.UC_ARM_REG_R0), uc.reg_read(arm.UC_ARM_REG_R1), self.count)

    def call_exact(self, name: str, *args: int) -> Call:
        """As `call`, counting with a hook on every instruction (slow; for --verify)."""
        hook = self.uc.hook_add(UC_HOOK_CODE, self._on_instruction)
        # Blocks translated before the hook was added would run without it.
        self.uc.ctl_flush_tb()
        self.exact = True
        self.raw_count = 0
        self.it_start = self.it_end = 0
        try:
            return self.call(name, *args)
        finally:
            self.exact = False
            self.uc.hook_del(hook)
            self.uc.ctl_flush_tb()

    def call_profiled(self, name: str, *args: int) -> list[tuple[str, int]]:
        """As `call`; returns the instructions executed in each function (symbol), most first."""
        self.profile = {}
        try:
            self.call(name, *args)
            by_function: dict[str, int] = {}
            for address, n in self.profile.items():
                function = self.function_at(address)
                by_function[function] = by_function.get(function, 0) + n
        finally:
            self.profile = None
        return sorted(by_function.items(), key=lambda item: -item[1])

    def function_at(self, address: int) -> str:
        i = bisect.bisect_right(self.functions, (address, 1 << 64, "")) - 1
        if i >= 0 and self.functions[i][0] <= address < self.functions[i][1]:
            return self.functions[i][2]
        return f"{address:#x}"

    # Stack -------------------------------------------------------------------------------------

    def paint_stack(self) -> None:
        self.uc.mem_write(self.stack_bottom, bytes([STACK_PAINT]) * (self.stack_top - self.stack_bottom))

    def stack_used(self) -> int:
        """Bytes of stack written since the last paint (the deepest any call went)."""
        memory = bytes(self.uc.mem_read(self.stack_bottom, self.stack_top - self.stack_bottom))
        untouched = len(memory) - len(memory.lstrip(bytes([STACK_PAINT])))
        return len(memory) - untouched

    # The probe's functions ---------------------------------------------------------------------

    def move(self, index: int) -> tuple[int, int, int, int]:
        self.call("probe_move", index, SCRATCH_PAGE)
        destination, velocity, acceleration, jerk = self.read_words(SCRATCH_PAGE, 4)
        return (destination - (1 << 32) if destination >= 1 << 31 else destination, velocity, acceleration, jerk)

    def phases(self) -> list[int]:
        self.call("probe_phases", SCRATCH_PAGE)
        return self.read_words(SCRATCH_PAGE, 7)


def demangle(name: str) -> str:
    """A Rust legacy-mangled name (`_ZN4core3fmt5write17h0123456789abcdefE`) as a path without
    its hash (`core::fmt::write`), a v0-mangled one roughly so; other names as they are."""
    if name.startswith("_R"):
        return demangle_v0(name)
    if not (name.startswith("_ZN") and name.endswith("E")):
        return name
    parts, i, body = [], 3, name[:-1]
    while i < len(body) and body[i].isdigit():
        j = i
        while body[j].isdigit():
            j += 1
        length = int(body[i:j])
        parts.append(body[j:j + length])
        i = j + length
    if parts and len(parts[-1]) == 17 and parts[-1].startswith("h"):
        parts.pop()
    # A component that starts with an escape gets a leading underscore.
    path = "::".join(part[1:] if part.startswith("_$") else part for part in parts)
    for escape, char in (("$LT$", "<"), ("$GT$", ">"), ("$RF$", "&"), ("$u20$", " "), ("$C$", ","),
                         ("$u7b$", "{"), ("$u7d$", "}"), ("..", "::")):
        path = path.replace(escape, char)
    return path


def demangle_v0(name: str) -> str:
    """The identifiers of a v0-mangled name joined by `::`, skipping crate disambiguators
    (`_RNvNtCs1a2b_17compiler_builtins3mem7memmove` → `compiler_builtins::mem::memmove`): enough
    to name a function, not a full demangler (generic arguments come out as more identifiers)."""
    parts, i = [], 2
    while i < len(name):
        if name[i].isdigit():
            j = i
            while j < len(name) and name[j].isdigit():
                j += 1
            length = int(name[i:j])
            if j < len(name) and name[j] == "_":  # separator before an identifier starting with _ or a digit
                j += 1
            parts.append(name[j:j + length])
            i = j + length
        elif name.startswith("Cs", i):
            i = name.find("_", i) + 1 or len(name)
        else:
            i += 1
    return "::".join(parts) or name


def merge(regions: list[tuple[int, int]]) -> list[tuple[int, int]]:
    merged: list[list[int]] = []
    for start, end in sorted(regions):
        if merged and start <= merged[-1][1]:
            merged[-1][1] = max(merged[-1][1], end)
        else:
            merged.append([start, end])
    return [(start, end) for start, end in merged]


def percentile(sorted_values: list[int], p: float) -> int:
    """Nearest-rank percentile."""
    rank = max(1, -(-len(sorted_values) * p // 100))
    return sorted_values[int(rank) - 1]


REFUSED = (1 << 64) - 1


# Planning ----------------------------------------------------------------------------------------


def measure_planning(probe: Probe, first: int, n: int) -> list[tuple[int, int, tuple[int, int, int, int], int]]:
    """(index, instructions, move, total cycles) for moves first .. first+n-1."""
    results = []
    for index in range(first, first + n):
        move = probe.move(index)
        call = probe.call("probe_plan_bits", *move)
        if call.u64 == REFUSED:
            raise ProbeFailure(f"move {index} was refused: {describe_move(move)}")
        results.append((index, call.instructions, move, call.u64))
    return results


def measure_hard(probe: Probe, moves: str, sub_counts: str) -> list[int]:
    """Counts the listed moves: random-move indices (`probe_plan_bits` on move `i`) and moves from
    fractional positions written `distance:velocity:acceleration:jerk` (`probe_plan_sub_count`),
    each list comma-separated: the costliest the surveys found (README), held to the planning
    budget so that a change cannot bring one of them back over it unseen."""
    print("== planning the surveys' costliest moves")
    results = []
    for index in [int(i) for i in moves.split(",") if i]:
        move = probe.move(index)
        call = probe.call("probe_plan_bits", *move)
        if call.u64 == REFUSED:
            raise ProbeFailure(f"move {index} was refused: {describe_move(move)}")
        print(f"    move {index}: {call.instructions} instructions; {describe_move(move)}; {call.u64} cycles")
        results.append(call.instructions)
    for listed in [m for m in sub_counts.split(",") if m]:
        distance, velocity, acceleration, jerk = (int(x) for x in listed.split(":"))
        call = probe.call("probe_plan_sub_count", distance, velocity, acceleration, jerk)
        if call.u64 == REFUSED:
            raise ProbeFailure(f"refused: {distance} raw units, V {velocity}, A {acceleration}, J {jerk}")
        print(f"    {call.instructions} instructions: {distance} raw units, V {velocity}, A {acceleration}, "
              f"J {jerk}; {call.u64} cycles")
        results.append(call.instructions)
    return results


def measure_sub_count(probe: Probe, n: int, top: int, seed: int = 17) -> list[int]:
    """Counts `probe_plan_sub_count` on `n` random moves of the class `pure_jerk` plans: a jerk of
    1 to 15 raw units, a distance log-uniform over 2 .. 2^17 raw units to a fractional position,
    the velocity and acceleration registers log-uniform over their ranges."""
    rng = random.Random(seed)
    print(f"== planning from fractional positions: probe_plan_sub_count over {n} moves (seed {seed})")
    results = []
    for _ in range(n):
        distance = max(2, int(2 ** rng.uniform(1, 17)))
        velocity = max(1, int(2 ** rng.uniform(0, 30)))
        acceleration = max(1, int(2 ** rng.uniform(0, 15)))
        jerk = rng.randint(1, 15)
        call = probe.call("probe_plan_sub_count", distance, velocity, acceleration, jerk)
        if call.u64 == REFUSED:
            raise ProbeFailure(f"refused: {distance} raw units, V {velocity}, A {acceleration}, J {jerk}")
        results.append((call.instructions, distance, velocity, acceleration, jerk, call.u64))
    counts = sorted(r[0] for r in results)
    print(f"  instructions: p50 {percentile(counts, 50)}, p99 {percentile(counts, 99)}, "
          f"worst {counts[-1]}, mean {statistics.fmean(counts):.0f}")
    for n_, distance, velocity, acceleration, jerk, total in sorted(results, key=lambda r: -r[0])[:top]:
        print(f"    {n_} instructions: {distance} raw units, V {velocity}, A {acceleration}, J {jerk}; "
              f"{total} cycles")
    return counts


def measure_replans(probe: Probe, n: int, top: int) -> list[int]:
    """Counts `probe_replan_bits` on the first `n` random moves: each planned in place into a
    generator at rest on 0 (`SCurve::set_parameters`), the generator reset before each call
    (uncounted): starting a move as firmware that keeps its generator does."""
    print(f"== planning in place: probe_replan_bits over moves 0 .. {n - 1} (set_parameters at rest)")
    results = []
    for index in range(n):
        move = probe.move(index)
        if probe.call("probe_replan_reset").r0 != 0:
            raise ProbeFailure("probe_replan_reset failed")
        call = probe.call("probe_replan_bits", *move)
        if call.u64 == REFUSED:
            raise ProbeFailure(f"move {index} was refused in place: {describe_move(move)}")
        results.append((call.instructions, index, move))
    counts = sorted(r[0] for r in results)
    over = sum(1 for c in counts if c > 20_000)
    print(f"  instructions: p50 {percentile(counts, 50)}, p99 {percentile(counts, 99)}, "
          f"worst {counts[-1]}, mean {statistics.fmean(counts):.0f}; {over} over 20,000")
    for n_, index, move in sorted(results, key=lambda r: -r[0])[:top]:
        print(f"    move {index}: {n_} instructions; {describe_move(move)}")
    return counts


# Stepping ----------------------------------------------------------------------------------------

PHASE_NAMES = ("ramp (I-III)", "cruise (IV)", "deceleration (V-VII)", "at rest (after the move)")


def step_move(probe: Probe, move: tuple[int, int, int, int], rest_cycles: int,
              per_phase: list[list[int]], worst: dict) -> int:
    """Steps `move` to its end (and `rest_cycles` more); adds each cycle's count to its phase.
    Returns the number of cycles stepped."""
    setup = probe.call("probe_step_setup", *move)
    total = setup.u64
    if total == REFUSED:
        raise ProbeFailure(f"step move refused: {describe_move(move)}")
    phases = probe.phases()
    probe.paint_stack()  # the steps' own stack, not the planning's
    ramp_end = min(sum(phases[0:3]), total)
    deceleration_start = max(total - sum(phases[4:7]), ramp_end)
    for cycle in range(1, total + rest_cycles + 1):
        n = probe.call("probe_step").instructions
        phase = 0 if cycle <= ramp_end else 1 if cycle <= deceleration_start else 2 if cycle <= total else 3
        per_phase[phase].append(n)
        if n > worst["instructions"]:
            worst.update(instructions=n, move=move, cycle=cycle, total=total, phase=PHASE_NAMES[phase])
    worst["stack"] = max(worst.get("stack", 0), probe.stack_used())
    return total + rest_cycles


# The other generators ------------------------------------------------------------------------------

# Velocity contouring: the bench move (100 counts/cycle at 0.25 counts/cycle², D = A) and a
# reversal (-100 at 0.25 up, 0.125 down), raw Juno bits (16.16, 8.24).
FIXED_VELOCITY_MOVES = ((100 << 16, 1 << 22, 0), (-(100 << 16), 1 << 22, 1 << 21))
# The trapezoid's bench move: 1,000,000 counts at 100 counts/cycle, 0.25 counts/cycle², D = A.
FIXED_TRAPEZOID_MOVE = (1_000_000, 100 << 16, 1 << 22, 0, 0)


def random_trapezoid_moves(n: int, seed: int = 12) -> list[tuple[int, int, int, int, int]]:
    """Deterministic moves from rest, each at most ~3,000 cycles long: a distance log-uniform in
    1 .. 10^6 counts (either sign), the velocity and rates log-uniform above the bounds that keep
    the move short, a separate deceleration 2/3 of the time, a starting velocity 1/3 of the time."""
    import math
    import random
    rng = random.Random(seed)
    log_uniform = lambda low, high: int(math.exp(rng.uniform(math.log(low), math.log(high))))
    moves = []
    for _ in range(n):
        distance = log_uniform(1, 1_000_000)
        velocity = log_uniform(max(1, distance * 65536 // 1000), 2**31 - 1)
        min_rate = max(1, 4 * distance * 2**24 // 1000**2)
        acceleration = log_uniform(min_rate, 2**31 - 1)
        deceleration = 0 if rng.random() < 1 / 3 else log_uniform(min_rate, 2**31 - 1)
        start = int(velocity * rng.random()) if rng.random() < 1 / 3 else 0
        moves.append((distance if rng.random() < 0.5 else -distance, velocity, acceleration, deceleration, start))
    return moves


def full_range_trapezoid_moves(n: int, seed: int = 15) -> list[tuple[int, int, int, int, int]]:
    """Deterministic moves across the whole register ranges (set-up only, not stepped): distance,
    maximum velocity, acceleration and deceleration (zero a third of the time) log-uniform over
    their registers, a starting velocity (uniform below the maximum) two thirds of the time."""
    import math
    import random
    rng = random.Random(seed)
    log_uniform = lambda low, high: int(math.exp(rng.uniform(math.log(low), math.log(high))))
    moves = []
    for _ in range(n):
        distance = min(log_uniform(1, 2**31 - 1), 2**31 - 1) * rng.choice([-1, 1])
        velocity = log_uniform(1, 2**31 - 1)
        acceleration = log_uniform(1, 2**31 - 1)
        deceleration = 0 if rng.random() < 1 / 3 else log_uniform(1, 2**31 - 1)
        start = int(velocity * rng.random()) if rng.random() < 2 / 3 else 0
        moves.append((max(-2**31, distance), velocity, acceleration, deceleration, start))
    return moves


def measure_setups(probe: Probe, moves: list[tuple[int, int, int, int, int]]) -> list[tuple[int, tuple]]:
    """The trapezoid's set-up count (`probe_trapezoid_setup`) of each move."""
    counts = []
    for move in moves:
        probe.uc.mem_write(SCRATCH_PAGE, struct.pack("<5I", *(w & 0xFFFF_FFFF for w in move)))
        setup = probe.call("probe_trapezoid_setup", SCRATCH_PAGE)
        if setup.r0:
            raise ProbeFailure(f"trapezoid move refused: {move}")
        counts.append((setup.instructions, move))
    return counts


def measure_gear(probe: Probe) -> list[int]:
    """Per-cycle counts of `ElectronicGear::follow` (SPEC §14), each cycle one call: engaged at
    ratios from tiny to the register's extremes, with masters whose count moves by random steps
    (wrapping past ±2³¹ too), then a smooth stop to rest, a new ratio, an abrupt stop and its
    cycles at rest."""
    import random
    rng = random.Random(14)
    counts = []
    for ratio in (1, -1, 1 << 16, 3 << 15, -(5 << 14), 1_073_741_823, -1_073_741_824):
        if probe.call("probe_gear_setup", ratio & 0xFFFF_FFFF, 1 << 20).r0:
            raise ProbeFailure(f"gear ratio {ratio} refused")
        master = rng.randrange(-(1 << 31), 1 << 31)
        speed = rng.choice((1, 7, 1_000, 1 << 20))
        def follow(cycles: int) -> None:
            nonlocal master
            for _ in range(cycles):
                master = (master + rng.randrange(-speed, speed + 1) + (1 << 31)) % (1 << 32) - (1 << 31)
                counts.append(probe.call("probe_gear_follow", master & 0xFFFF_FFFF).instructions)
        follow(300)
        probe.call("probe_gear_command", 0, 0)  # smooth stop: decelerate to rest
        follow(2_000)
        probe.call("probe_gear_command", 2, (ratio // 2) & 0xFFFF_FFFF)  # re-engaged
        follow(300)
        probe.call("probe_gear_command", 1, 0)  # abrupt stop
        follow(20)
    return counts


def measure_other_generators(probe: Probe, moves: int) -> tuple[dict[str, list[int]], list[int]]:
    """Per-cycle counts of VelocityContouring, Trapezoidal and ElectronicGear, and the trapezoid's
    set-up counts."""
    steps: dict[str, list[int]] = {"VelocityContouring": [], "Trapezoidal": [], "ElectronicGear": []}
    steps["ElectronicGear"] = measure_gear(probe)
    for velocity, acceleration, deceleration in FIXED_VELOCITY_MOVES:
        if probe.call("probe_velocity_setup", velocity & 0xFFFF_FFFF, acceleration, deceleration).r0:
            raise ProbeFailure("velocity move refused")
        steps["VelocityContouring"] += [probe.call("probe_velocity_step").instructions for _ in range(2_000)]
    setups = []
    for move in [FIXED_TRAPEZOID_MOVE] + random_trapezoid_moves(moves):
        probe.uc.mem_write(SCRATCH_PAGE, struct.pack("<5I", *(w & 0xFFFF_FFFF for w in move)))
        setup = probe.call("probe_trapezoid_setup", SCRATCH_PAGE)
        if setup.r0:
            raise ProbeFailure(f"trapezoid move refused: {move}")
        setups.append(setup.instructions)
        for cycle in range(20_000):
            steps["Trapezoidal"].append(probe.call("probe_trapezoid_step").instructions)
            if probe.call("probe_trapezoid_complete").r0:
                break
        else:
            raise ProbeFailure(f"trapezoid move {move} did not arrive in 20,000 cycles")
        steps["Trapezoidal"] += [probe.call("probe_trapezoid_step").instructions for _ in range(2)]
    return steps, setups


# Linear interpolation ------------------------------------------------------------------------------

# The manual's line (reference 003): finish (-20000, 30000, -50000), and its MCX514 registers at a
# 1 ms cycle: SV 500 pps, DV 20,000 pps, AC = DC = 65,000 pps/s (0.5 and 20 pulses/cycle, 0.065
# pulses/cycle²), automatic, manual at 45,000 and disabled deceleration.
MANUAL_LINE = (-20_000, 30_000, -50_000)
MANUAL_LINE_MCX514 = [(1000, 500, 20_000, 65_000, 65_000, mode, 45_000) for mode in (0, 1, 2)]
# The same line driven by the crate's trapezoid: 20 steps/cycle (16.16), 0.065 steps/cycle² (8.24).
MANUAL_LINE_TRAPEZOID = (20 << 16, round(0.065 * 2**24), 0, 0)
LINE_PROFILES = ("mcx514", "trapezoid", "mcx514_scurve", "", "", "scurve")
# The manual's line driven by the MCX514 S-curve: the same registers, JK = DJ = 650,000 pps/s²
# (the rate reaches AC in 0.1 s).
MANUAL_LINE_MCX514_SCURVE = [registers + (650_000, 650_000) for registers in MANUAL_LINE_MCX514]


def random_line(rng, steps: int) -> tuple[int, int, int]:
    """A 3-axis finish point whose long axis is `steps` pulses: the long axis at a random place and
    sign, the others anywhere within it."""
    axes = [rng.randint(-steps, steps) for _ in range(3)]
    axes[rng.randrange(3)] = steps if rng.random() < 0.5 else -steps
    return tuple(axes)


def random_mcx514_lines(n: int, seed: int = 14) -> list[tuple[tuple[int, int, int], tuple]]:
    """Deterministic MCX514-driven lines of at most a few thousand cycles: L log-uniform in
    1 .. 10^6 pulses, a cycle of 100 µs, 250 µs or 1 ms, DV and AC log-uniform above the bounds
    that keep the move short, SV log-uniform up to DV, automatic (AC = DC), manual (a random
    point and DC) or disabled deceleration."""
    import math
    import random
    rng = random.Random(seed)
    log_uniform = lambda low, high: int(math.exp(rng.uniform(math.log(low), math.log(max(low, high)))))
    lines = []
    for _ in range(n):
        steps = log_uniform(1, 1_000_000)
        cycle_us = rng.choice((100, 250, 1000))
        cycle = cycle_us * 1e-6
        drive = log_uniform(max(1, math.ceil(steps / (2000 * cycle))), 8_000_000)
        initial = log_uniform(max(1, math.ceil(steps / (8000 * cycle))), drive) if rng.random() < 0.9 \
            else drive
        initial = min(initial, drive)
        acceleration = log_uniform(max(1, math.ceil(drive / (1500 * cycle))), 536_870_911)
        mode = rng.choice((0, 1, 2))
        deceleration = acceleration if mode != 1 else log_uniform(
            max(1, math.ceil(drive / (1500 * cycle))), 536_870_911)
        point = rng.randint(0, steps)
        lines.append((random_line(rng, steps), (cycle_us, initial, drive, acceleration, deceleration, mode, point)))
    return lines


def random_mcx514_scurve_lines(n: int, seed: int = 16) -> list[tuple[tuple[int, int, int], tuple]]:
    """The random MCX514 lines with jerks: JK log-uniform above the bound that lets the rate reach
    AC in 1,500 cycles (or the whole range), DJ = JK for automatic deceleration."""
    import math
    import random
    rng = random.Random(seed)
    log_uniform = lambda low, high: int(math.exp(rng.uniform(math.log(low), math.log(max(low, high)))))
    lines = []
    for finish, registers in random_mcx514_lines(n, seed):
        cycle_us, initial, drive, acceleration, deceleration, mode, point = registers
        cycle = cycle_us * 1e-6
        low = lambda rate: min(1_073_741_823, max(1, math.ceil(rate / (1500 * cycle))))
        jerk = log_uniform(low(acceleration), 1_073_741_823)
        deceleration_jerk = jerk if mode == 0 else log_uniform(low(deceleration), 1_073_741_823)
        lines.append((finish, registers + (jerk, deceleration_jerk)))
    return lines


def random_trapezoid_lines(n: int, seed: int = 15) -> list[tuple[tuple[int, int, int], tuple]]:
    """Deterministic trapezoid-driven lines: the random trapezoid moves' registers, the distance
    as the long axis."""
    import random
    rng = random.Random(seed)
    return [(random_line(rng, abs(distance)), (velocity, acceleration, deceleration, start))
            for distance, velocity, acceleration, deceleration, start in random_trapezoid_moves(n, seed)]


def step_line(probe: Probe, profile: str, finish: tuple[int, int, int], registers: tuple,
              counts: list[int], max_cycles: int = 20_000) -> None:
    """Sets up and steps one line to its end (and 2 cycles more), each cycle's count to `counts`;
    checks that it ends on the finish point."""
    kind = LINE_PROFILES.index(profile)
    words = [kind, *finish, *registers]
    words += [0] * (13 - len(words))
    probe.uc.mem_write(SCRATCH_PAGE, struct.pack("<13I", *(w & 0xFFFF_FFFF for w in words)))
    if probe.call("probe_line_setup", SCRATCH_PAGE).u64 == REFUSED:
        raise ProbeFailure(f"line {finish} driven by {profile} {registers} refused")
    for _ in range(max_cycles):
        counts.append(probe.call(f"probe_line_step_{profile}").instructions)
        if probe.call("probe_line_complete", SCRATCH_PAGE + 64).r0:
            break
    else:
        raise ProbeFailure(f"line {finish} driven by {profile} {registers}: not complete in {max_cycles} cycles")
    counts += [probe.call(f"probe_line_step_{profile}").instructions for _ in range(2)]
    axes = [a - (1 << 32) if a >= 1 << 31 else a for a in probe.read_words(SCRATCH_PAGE + 64, 3)]
    if tuple(axes) != finish:
        raise ProbeFailure(f"line {finish} driven by {profile} {registers} ended at {axes}")


def step_axis(probe: Probe, profile: str, finish: tuple[int, int, int], registers: tuple,
              counts: list[int], max_cycles: int = 20_000) -> int:
    """Sets up the MCX514 profile (`mcx514` the trapezoid, `mcx514_scurve` the S-curve) of a line
    alone (no geometry: a one-axis generator) and steps it to its end (and 2 cycles more), each
    cycle's count to `counts`; returns the set-up's count (the line's steps, the registers'
    conversion from pps with the cycle time, the plan)."""
    kind = {"mcx514": 3, "mcx514_scurve": 4}[profile]
    words = [kind, *finish, *registers]
    words += [0] * (13 - len(words))
    probe.uc.mem_write(SCRATCH_PAGE, struct.pack("<13I", *(w & 0xFFFF_FFFF for w in words)))
    setup = probe.call("probe_line_setup", SCRATCH_PAGE)
    if setup.u64 == REFUSED:
        raise ProbeFailure(f"axis {finish} {profile} {registers} refused")
    for _ in range(max_cycles):
        counts.append(probe.call(f"probe_axis_step_{profile}").instructions)
        if probe.call("probe_axis_complete").r0:
            break
    else:
        raise ProbeFailure(f"axis {profile} {registers}: not complete in {max_cycles} cycles")
    counts += [probe.call(f"probe_axis_step_{profile}").instructions for _ in range(2)]
    return setup.instructions


def measure_mcx514_axis(probe: Probe, moves: int) -> dict[str, tuple[list[int], list[int]]]:
    """Per-cycle counts of the MCX514 trapezoid and S-curve alone, over the lines' drives, and
    their set-up counts."""
    drives = {
        "mcx514": [(MANUAL_LINE, r) for r in MANUAL_LINE_MCX514] + random_mcx514_lines(moves),
        "mcx514_scurve": [(MANUAL_LINE, r) for r in MANUAL_LINE_MCX514_SCURVE]
        + random_mcx514_scurve_lines(moves),
    }
    measured = {}
    for profile, lines in drives.items():
        counts: list[int] = []
        setups = [step_axis(probe, profile, finish, registers, counts) for finish, registers in lines]
        measured[profile] = (counts, setups)
    return measured


def random_mcx514_scurve_registers(n: int, seed: int = 17) -> list[tuple[tuple[int, int, int], tuple]]:
    """MCX514 S-curve lines with every register log-uniform over its whole range (the cycle time
    one of 100, 250, 1,000, 4,000 µs; SV ≤ DV; AC = DC and JK = DJ with automatic deceleration;
    any manual point), for planning only: such moves can take billions of cycles."""
    import math
    import random
    rng = random.Random(seed)
    log_uniform = lambda low, high: int(math.exp(rng.uniform(math.log(low), math.log(high))))
    lines = []
    for _ in range(n):
        cycle = rng.choice([100, 250, 1000, 4000])
        a, b = log_uniform(1, 8_000_000), log_uniform(1, 8_000_000)
        mode = rng.randrange(3)
        acceleration = log_uniform(1, 536_870_911)
        deceleration = acceleration if mode == 0 else log_uniform(1, 536_870_911)
        jerk = log_uniform(1, 1_073_741_823)
        deceleration_jerk = jerk if mode == 0 else log_uniform(1, 1_073_741_823)
        steps = log_uniform(1, (1 << 30) - 1)
        finish = (steps, log_uniform(1, steps) * rng.choice([-1, 1]), 0)
        lines.append((finish, (cycle, min(a, b), max(a, b), acceleration, deceleration, mode,
                               rng.randint(0, steps), jerk, deceleration_jerk)))
    return lines


def measure_mcx514_plans(probe: Probe, moves: int) -> list[int]:
    """The MCX514 S-curve's plan (`Layout::lay_out` and every function it calls) counted alone, at
    the set-up of random moves over the whole register ranges: the set-up also converts the
    registers from pps with f64 arithmetic, emulated on this core (the units' edge, not the
    planning). Set-ups the crate refuses (a register that vanishes per cycle) are skipped."""
    starts = {start for start, _, name in probe.functions if "mcx514::scurve::plan::Layout::lay_out" in name}
    if not starts:
        raise ProbeFailure("no mcx514::scurve::plan::Layout::lay_out in the probe image")
    inside = {"return": None, "count": 0}

    def on_instruction(uc, address, _size, _data) -> None:
        if inside["return"] is None:
            if address in starts:
                inside["return"] = uc.reg_read(arm.UC_ARM_REG_LR) & ~1
                inside["count"] += 1
        elif address == inside["return"]:
            inside["return"] = None
        else:
            inside["count"] += 1

    hook = probe.uc.hook_add(UC_HOOK_CODE, on_instruction)
    probe.uc.ctl_flush_tb()
    plans: list[int] = []
    try:
        for finish, registers in random_mcx514_scurve_registers(moves):
            words = [4, *finish, *registers]
            probe.uc.mem_write(SCRATCH_PAGE, struct.pack("<13I", *(w & 0xFFFF_FFFF for w in words)))
            inside["count"] = 0
            if probe.call("probe_line_setup", SCRATCH_PAGE).u64 != REFUSED:
                plans.append(inside["count"])
    finally:
        probe.uc.hook_del(hook)
        probe.uc.ctl_flush_tb()
    return plans


def random_scurve_lines(moves: list[tuple[int, int, int, int]], seed: int = 18) -> list[tuple[tuple[int, int, int], tuple]]:
    """S-curve-driven lines: the given S-curve moves' registers, the distance (its size) as the
    long axis."""
    import random
    rng = random.Random(seed)
    return [(random_line(rng, abs(destination)), (velocity, acceleration, jerk))
            for destination, velocity, acceleration, jerk in moves if destination != 0]


def measure_lines(probe: Probe, moves: int, scurve_moves: list[tuple[int, int, int, int]]) -> dict[str, list[int]]:
    """Per-cycle counts of a 3-axis line (profile plus geometry), per driving profile; the
    crate's S-curve drives lines of `scurve_moves` (destination, velocity, acceleration, jerk
    bits)."""
    counts: dict[str, list[int]] = {profile: [] for profile in LINE_PROFILES if profile}
    for registers in MANUAL_LINE_MCX514:
        step_line(probe, "mcx514", MANUAL_LINE, registers, counts["mcx514"])
    step_line(probe, "trapezoid", MANUAL_LINE, MANUAL_LINE_TRAPEZOID, counts["trapezoid"])
    for finish, registers in random_mcx514_lines(moves):
        step_line(probe, "mcx514", finish, registers, counts["mcx514"])
    for finish, registers in random_trapezoid_lines(moves):
        step_line(probe, "trapezoid", finish, registers, counts["trapezoid"])
    for registers in MANUAL_LINE_MCX514_SCURVE:
        step_line(probe, "mcx514_scurve", MANUAL_LINE, registers, counts["mcx514_scurve"])
    for finish, registers in random_mcx514_scurve_lines(moves):
        step_line(probe, "mcx514_scurve", finish, registers, counts["mcx514_scurve"])
    for finish, registers in random_scurve_lines(scurve_moves):
        step_line(probe, "scurve", finish, registers, counts["scurve"])
    return counts


# The manual's circle (reference 003): r = 10,000 full turn, SV 500, DV 20,000 pps, AC = DC
# 65,000 pps/s, DP 53,493, at a 1 ms cycle: centre, finish, CCW, then the MCX514 registers.
MANUAL_CIRCLE = (10_000, 0, 0, 0, 1, 500, 20_000, 65_000, 65_000, 53_493, 1_000)


def random_circles(n: int, seed: int = 15) -> list[tuple[int, ...]]:
    """Deterministic MCX514 circles of about 1,000 cycles each: a radius log-uniform in 1 .. 2^27
    at a random angle (the start exactly on the circle: the centre is rounded, the radius follows),
    a full, half or quarter turn in either direction (the opposite and the quarter-turn points of
    an exact start are exact too), the cycle time and DV chosen so that about a thousand cycles
    cover the arc, SV a tenth of DV, AC = DC for a 100-cycle ramp, and the manual deceleration
    point the continuous-time ramp's pulses before the end."""
    import math
    import random
    rng = random.Random(seed)
    circles = []
    while len(circles) < n:
        radius = math.exp(rng.uniform(0, math.log(2**27)))
        angle = rng.uniform(0, 2 * math.pi)
        cx, cy = -round(radius * math.cos(angle)), -round(radius * math.sin(angle))
        if (cx, cy) == (0, 0):
            continue
        turn = rng.choice(("full", "half", "quarter"))
        # The start relative to the centre is (-cx, -cy); finishes relative to the start.
        finish = {"full": (0, 0), "half": (2 * cx, 2 * cy), "quarter": (cx + cy, cy - cx)}[turn]
        ccw = rng.randrange(2)
        if turn == "quarter" and not ccw:
            finish = (cx - cy, cy + cx)
        steps = 6 * math.hypot(cx, cy) * {"full": 1.0, "half": 0.5, "quarter": 0.25}[turn] + 1
        cycle_us = max(1_000, math.ceil(steps / 4_000_000 * 1e6 / 1_000))
        cycle = cycle_us * 1e-6
        drive = max(10, min(8_000_000, round(steps / 1_000 / cycle)))
        initial = max(1, drive // 10)
        acceleration = max(1, min(2**29 - 1, round((drive - initial) / (100 * cycle))))
        ramp = math.ceil((drive * drive - initial * initial) / (2 * acceleration))
        point = max(0, int(steps) - ramp)
        circles.append((cx, cy, *finish, ccw, initial, drive, acceleration, acceleration, point, cycle_us))
    return circles


def as_trapezoid(circle: tuple[int, ...]) -> tuple[int, ...]:
    """The same circle driven by the crate's `Trapezoidal`: DV·T as 16.16, AC·T² as 8.24."""
    *geometry, initial, drive, acceleration, _, _, cycle_us = circle
    cycle = cycle_us * 1e-6
    velocity = max(1, min(2**31 - 1, round(drive * cycle * 65536)))
    rate = max(1, min(2**31 - 1, round(acceleration * cycle * cycle * 2**24)))
    return (*geometry, 1, velocity, rate, 0, 0, 0, 0)


def measure_circles(probe: Probe, moves: int) -> dict[str, list[int]]:
    """Per-cycle counts of the circular interpolation (profile plus arc) per driving profile: the
    manual's circle and `moves` random ones, each to its end (a full turn back on its start)."""
    counts: dict[str, list[int]] = {"mcx514": [], "trapezoid": []}
    for circle in [MANUAL_CIRCLE] + random_circles(moves):
        *geometry, initial, drive, acceleration, deceleration, point, cycle_us = circle
        mcx514 = (*geometry, 0, initial, drive, acceleration, deceleration, point, cycle_us)
        for name, words in (("mcx514", mcx514), ("trapezoid", as_trapezoid(circle))):
            kind = 0 if name == "mcx514" else 1
            probe.uc.mem_write(SCRATCH_PAGE, struct.pack("<12I", *(w & 0xFFFF_FFFF for w in words)))
            if probe.call("probe_circle_setup", SCRATCH_PAGE).r0:
                raise ProbeFailure(f"circle refused: {words}")
            for _ in range(200_000):
                counts[name].append(probe.call(f"probe_circle_step_{name}").instructions)
                if probe.call("probe_circle_complete", kind).r0:
                    break
            else:
                raise ProbeFailure(f"circle {words} did not end in 200,000 cycles")
            counts[name].append(probe.call(f"probe_circle_step_{name}").instructions)
            end = probe.call("probe_circle_axes").u64
            if circle[2:4] == (0, 0) and end != 0:
                raise ProbeFailure(f"full circle {words} ended at {end:#x}, not at its start")
    return counts
def trapezoid_commands(n: int, seed: int = 13) -> list[tuple[tuple[int, int, int, int, int], int, list[tuple[int, int]]]]:
    """Deterministic moves (as `random_trapezoid_moves`) each with a script given in motion: the
    cycle of the first command, then one to three commands (the kinds of
    `probe_trapezoid_command`: smooth or abrupt stop, a new destination near or far, maximum
    velocity, acceleration or deceleration; an abrupt stop often followed by a new maximum
    velocity, which resumes the move after the stop's cycle)."""
    import math
    import random
    rng = random.Random(seed)
    log_uniform = lambda low, high: int(math.exp(rng.uniform(math.log(low), math.log(high))))
    scripts = []
    for move in random_trapezoid_moves(n, seed):
        destination, velocity, acceleration, deceleration, _ = move
        commands = []
        for _ in range(rng.randint(1, 3)):
            kind = rng.choice([0, 1, 1, 2, 2, 2, 3, 3, 4, 5])
            if kind == 2:
                scale = max(1, abs(destination))
                value = rng.choice([rng.randint(-scale, 2 * scale), rng.randint(-2**31, 2**31 - 1),
                                    destination + rng.randint(-3, 3)])
                value = max(-2**31, min(2**31 - 1, value))
            elif kind == 3:
                value = log_uniform(max(1, velocity // 1000), 2**31 - 1)
            elif kind in (4, 5):
                value = 0 if kind == 5 and rng.random() < 0.25 else log_uniform(max(1, acceleration // 1000), 2**31 - 1)
            else:
                value = 0
            commands.append((kind, value))
            if kind == 1 and rng.random() < 0.5:
                commands.append((3, velocity))
        scripts.append((move, rng.choice([0, 1, 2, rng.randint(0, 300)]), commands))
    return scripts


def drop_within_deceleration(acceleration: int, deceleration: int, start: int) -> bool:
    """The starting velocity (16.16) is at most the deceleration in force (8.24; 0 means A)."""
    return start << 16 <= (deceleration or acceleration) << 8


def measure_trapezoid_commands(probe: Probe, moves: int, after: int = 3000) -> tuple[list[int], list[int], list[int]]:
    """Per-cycle counts of the trapezoid after commands in motion (`trapezoid_commands`): every
    cycle from the first command on, up to `after` cycles after the last (or the end of the
    move). Returns the cycles of the moves whose starting velocity stays at most the
    deceleration, those of the others (a starting velocity above D, whose late braking may
    still decide cycle by cycle), and the commands' own counts (planning)."""
    within, beyond, commands = [], [], []
    for move, first, script in trapezoid_commands(moves):
        probe.uc.mem_write(SCRATCH_PAGE, struct.pack("<5I", *(w & 0xFFFF_FFFF for w in move)))
        if probe.call("probe_trapezoid_setup", SCRATCH_PAGE).r0:
            raise ProbeFailure(f"trapezoid move refused: {move}")
        _, _, acceleration, deceleration, start = move
        for _ in range(first):
            probe.call("probe_trapezoid_step")
        steps = []
        # The drop stays within D unless a command makes D (or A, standing in for it) smaller.
        ok = drop_within_deceleration(acceleration, deceleration, start)
        for index, (kind, value) in enumerate(script):
            commands.append(probe.call("probe_trapezoid_command", kind, value & 0xFFFF_FFFF).instructions)
            if kind == 4 and value:
                acceleration = value
            elif kind == 5 and 0 <= value < 2**31:
                deceleration = value
            ok &= drop_within_deceleration(acceleration, deceleration, start)
            gap = after if index == len(script) - 1 else probe_rng_gap(index)
            for _ in range(gap):
                steps.append(probe.call("probe_trapezoid_step").instructions)
                if probe.call("probe_trapezoid_complete").r0:
                    break
        (within if ok else beyond).extend(steps)
    return within, beyond, commands


def measure_other_commands(probe: Probe, moves: int, seed: int = 14
                           ) -> tuple[list[int], list[int], list[int], list[int], list[int]]:
    """Per-cycle counts after commands in motion of the S-curve (a smooth or abrupt stop, or both,
    at a random cycle of one of the planned random moves short enough to step; after half the
    abrupt ones a restart, right after the drop or later) and of velocity
    contouring (new velocities, rates and stops, several in a row), every cycle from the first
    command to the end (at most 5,000 cycles after the last); the S-curve's cycles after smooth
    stops alone and after stops that include an abrupt one, apart; and the S-curve stop commands'
    own counts (a smooth stop lays the whole stop out), those and smooth stops early in as many
    longer moves; and the restarts' own counts (`SCurve::restart`: a plan, into the generator
    that stopped)."""
    import math
    import random
    rng = random.Random(seed)
    log_uniform = lambda low, high: int(math.exp(rng.uniform(math.log(low), math.log(high))))
    restarts = random.Random(seed + 1)
    scurve, abrupt, velocity_counts, stops, restart_counts = [], [], [], [], []
    index = 0
    stepped = 0
    while stepped < moves and index < 20 * moves:
        move = probe.move(index)
        index += 1
        total = probe.call("probe_step_setup", *move).u64
        if total > 3000:
            continue
        stepped += 1
        for _ in range(rng.randint(0, max(0, total - 1))):
            probe.call("probe_step")
        kinds = rng.choice([[0], [1], [0, 1], [1, 0]])
        counts = abrupt if 1 in kinds else scurve
        for kind in kinds:
            stops.append(probe.call("probe_stop", kind).instructions)
            steps = rng.choice([0, 1, 3])
            for _ in range(steps):
                counts.append(probe.call("probe_step").instructions)
        if kinds[-1] == 1 and restarts.random() < 0.5:
            # Half the moves that end with an abrupt stop restart on the cycle after its drop
            # (its acceleration still the drop's, which the first step corrects) or later, to
            # the move's destination halved at its velocity (a separate generator of choices,
            # so the other moves stay as they were).
            if steps == 0:
                counts.append(probe.call("probe_step").instructions)
            restarted = probe.call("probe_restart", (move[0] // 2) & 0xFFFF_FFFF, move[1])
            if restarted.r0:
                raise ProbeFailure(f"restart of move {index - 1} refused")
            restart_counts.append(restarted.instructions)
        for _ in range(5000):
            counts.append(probe.call("probe_step").instructions)
            if probe.call("probe_complete").r0:
                break
        counts += [probe.call("probe_step").instructions for _ in range(2)]
    # Smooth stop commands in any move (over the whole ranges: the stop's own layout, not stepped
    # to its end): at a random one of its first 2,000 cycles.
    stepped = 0
    while stepped < moves and index < 40 * moves:
        move = probe.move(index)
        index += 1
        total = probe.call("probe_step_setup", *move).u64
        if total <= 3000:
            continue
        stepped += 1
        for _ in range(rng.randint(1, 2000)):
            probe.call("probe_step")
        stops.append(probe.call("probe_stop", 0).instructions)
    for _ in range(moves):
        velocity = log_uniform(1, 2**31 - 1) * rng.choice([-1, 1])
        acceleration = log_uniform(1 << 8, 2**31 - 1)
        if probe.call("probe_velocity_setup", velocity & 0xFFFF_FFFF, acceleration, 0).r0:
            raise ProbeFailure("velocity move refused")
        for _ in range(rng.randint(0, 200)):
            probe.call("probe_velocity_step")
        for _ in range(rng.randint(1, 4)):
            kind = rng.choice([0, 1, 2, 2, 3, 4])
            value = {2: log_uniform(1, 2**31 - 1) * rng.choice([-1, 1]),
                     3: log_uniform(1 << 8, 2**31 - 1), 4: rng.choice([0, log_uniform(1 << 8, 2**31 - 1)])}.get(kind, 0)
            probe.call("probe_velocity_command", kind, value & 0xFFFF_FFFF)
            for _ in range(rng.choice([0, 1, 50])):
                velocity_counts.append(probe.call("probe_velocity_step").instructions)
        velocity_counts += [probe.call("probe_velocity_step").instructions for _ in range(1000)]
    return scurve, abrupt, velocity_counts, stops, restart_counts


def probe_rng_gap(index: int) -> int:
    """The cycles between two commands of a script: 0, 1 and 7 in turn (commands before the
    first one's runs have begun, and a few cycles into them)."""
    return (0, 1, 7)[index % 3]


# Verification ------------------------------------------------------------------------------------


def verify(probe: Probe, moves: int, steps: int) -> bool:
    ok = True
    for index in range(moves):
        move = probe.move(index)
        fast = probe.call("probe_plan_bits", *move)
        exact = probe.call_exact("probe_plan_bits", *move)
        on_target = probe.call("probe_plan", index)
        same = fast.instructions == exact.instructions and fast.u64 == exact.u64
        skipped = exact.instructions - probe.raw_count
        print(f"  verify plan {index}: fast {fast.instructions} exact {exact.instructions} "
              f"({probe.raw_count} hooked + {skipped} failing their IT condition) "
              f"{'ok' if same else 'MISMATCH'}; total {fast.u64} cycles, probe_plan({index}) "
              f"{'agrees' if on_target.u64 == fast.u64 else 'DISAGREES: ' + str(on_target.u64)}")
        ok &= same and on_target.u64 == fast.u64
    # The failures this harness must catch.
    for name, expected in (("probe_selftest_panic", "panicked at src/main.rs"),
                           ("probe_selftest_runaway", "ran away")):
        cap, probe.max_instructions = probe.max_instructions, 100_000
        try:
            probe.call(name, 1)
            caught = "returned"
        except ProbeFailure as failure:
            caught = str(failure)
        finally:
            probe.max_instructions = cap
        good = expected in caught
        print(f"  self-test {name}: {'caught' if good else 'NOT CAUGHT'} ({caught})")
        ok &= good
    # Stepping: the fixed move, counted both ways on alternate copies (same setup, same cycles).
    fast_counts, exact_counts = [], []
    for counts, call in ((fast_counts, probe.call), (exact_counts, probe.call_exact)):
        total = probe.call("probe_step_setup", *FIXED_STEP_MOVE).u64
        for _ in range(min(steps, total + 2)):
            counts.append(call("probe_step").instructions)
    same = fast_counts == exact_counts
    print(f"  verify step: {len(fast_counts)} cycles of the fixed move, fast sum {sum(fast_counts)} "
          f"exact sum {sum(exact_counts)}, every cycle {'equal' if same else 'NOT equal'}")
    return ok and same


# Main --------------------------------------------------------------------------------------------


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--elf", default=DEFAULT_ELF, help="the probe image (default: %(default)s)")
    parser.add_argument("--moves", type=int, default=1000, help="random moves planned (default %(default)s)")
    parser.add_argument("--first-move", type=int, default=0, help="index of the first move (default 0)")
    parser.add_argument("--step-moves", type=int,
                        help="of the planned moves, how many (from the first) are also stepped to the end "
                             "when short enough (default: all)")
    parser.add_argument("--step-max-cycles", type=int, default=3000,
                        help="longest random move stepped, cycles (default %(default)s)")
    parser.add_argument("--plan-budget", type=int, help="fail when any plan executes more instructions")
    parser.add_argument("--step-budget", type=int, help="fail when any step executes more instructions")
    parser.add_argument("--setup-budget", type=int,
                        help="fail when any trapezoid set-up (starting a move) executes more instructions")
    parser.add_argument("--stop-budget", type=int,
                        help="fail when any S-curve stop command (with --command-moves) executes more "
                             "instructions")
    parser.add_argument("--max-instructions", type=int, default=50_000_000,
                        help="one call running longer than this is a runaway (default %(default)s)")
    parser.add_argument("--verify", action="store_true",
                        help="first check the block-based count against a per-instruction count")
    parser.add_argument("--verify-moves", type=int, default=3, help="plans checked by --verify (default 3)")
    parser.add_argument("--verify-steps", type=int, default=2000, help="steps checked by --verify (default 2000)")
    parser.add_argument("--trapezoid-moves", type=int, default=200,
                        help="random trapezoid moves stepped to the end (default %(default)s)")
    parser.add_argument("--line-moves", type=int, default=100,
                        help="random 3-axis lines stepped to the end, per driving profile (default %(default)s)")
    parser.add_argument("--line-budget", action="append", default=[], metavar="PROFILE=N",
                        help="fail when a cycle of a 3-axis line driven by PROFILE (mcx514, trapezoid, mcx514_scurve, scurve) "
                             "executes more than N instructions (profile plus geometry); repeatable")
    parser.add_argument("--mcx514-plan-moves", type=int, default=500,
                        help="random MCX514 S-curve moves over the whole register ranges whose plan is "
                             "counted (default %(default)s)")
    parser.add_argument("--mcx514-plan-budget", type=int,
                        help="fail when the MCX514 S-curve's plan executes more instructions")
    parser.add_argument("--circle-moves", type=int, default=20,
                        help="random MCX514 circles stepped to the end, besides the manual's (default %(default)s)")
    parser.add_argument("--circle-budget", action="append", default=[], metavar="PROFILE=N",
                        help="fail when a cycle of a circle driven by PROFILE (mcx514, trapezoid) executes "
                             "more than N instructions; repeatable")
    parser.add_argument("--setup-moves", type=int, default=0,
                        help="random trapezoid moves across the whole register ranges whose set-up is "
                             "counted (reported; default %(default)s)")
    parser.add_argument("--command-moves", type=int, default=300,
                        help="random trapezoid moves given commands in motion (default %(default)s)")
    parser.add_argument("--sub-count-moves", type=int, default=0,
                        help="random moves of under 2^17 raw units with a jerk of 1 to 15 raw units, from "
                             "fractional positions (what stops leave), whose plan is counted (reported; "
                             "default %(default)s)")
    parser.add_argument("--sub-count-seed", type=int, default=17,
                        help="the seed of the --sub-count-moves sample (default %(default)s, CI's; the "
                             "README's other samples are 99, 5, 1234 and 2026)")
    parser.add_argument("--hard-moves", default="", metavar="I,J,...",
                        help="random-move indices also planned and held to --plan-budget (the surveys' costliest)")
    parser.add_argument("--hard-sub-counts", default="", metavar="D:V:A:J,...",
                        help="moves from fractional positions (raw distance, velocity, acceleration, jerk) also "
                             "planned and held to --plan-budget")
    parser.add_argument("--replan-moves", type=int, default=0,
                        help="random moves (the first N of --moves' list) planned in place into a "
                             "generator at rest, SCurve::set_parameters (reported; default %(default)s)")
    parser.add_argument("--replan-budget", type=int,
                        help="fail when a plan of the --replan-moves executes more instructions")
    parser.add_argument("--sub-count-ceiling", type=int,
                        help="fail when a plan of the --sub-count-moves executes more instructions (CI: "
                             "SPEC §16's 20,000, which its sample meets and the class nearly does, issue "
                             "#11)")
    parser.add_argument("--functions", type=int, default=8,
                        help="functions listed for the worst plan (default %(default)s)")
    parser.add_argument("--top", type=int, default=5, help="the most expensive plans listed (default 5)")
    args = parser.parse_args()

    line_budgets: dict[str, int] = {}
    for budget in args.line_budget:
        name, _, value = budget.partition("=")
        if name not in LINE_PROFILES or not value.isdigit():
            parser.error(f"--line-budget {budget!r}: expected PROFILE=N with PROFILE one of {', '.join(LINE_PROFILES)}")
        line_budgets[name] = int(value)

    if not os.path.exists(args.elf):
        print(f"error: no probe image at {args.elf}: build it first "
              "(cd probe && cargo build --release)", file=sys.stderr)
        return 2
    probe = Probe(args.elf, args.max_instructions)
    started = time.monotonic()
    try:
        if args.verify:
            print("== verification: block-hook count vs per-instruction count")
            if not verify(probe, args.verify_moves, args.verify_steps):
                print("error: the fast count does not match the exact count", file=sys.stderr)
                return 2
            probe.paint_stack()

        planning_started = time.monotonic()
        print(f"== planning: probe_plan_bits over moves {args.first_move} .. {args.first_move + args.moves - 1}")
        results = measure_planning(probe, args.first_move, args.moves)
        plan_stack = probe.stack_used()
        counts = sorted(r[1] for r in results)
        worst = max(results, key=lambda r: r[1])
        print(f"  instructions: p50 {percentile(counts, 50)}, p99 {percentile(counts, 99)}, "
              f"worst {counts[-1]}, mean {statistics.fmean(counts):.0f}, best {counts[0]}")
        print(f"  worst: move {worst[0]}: {describe_move(worst[2])}; {worst[3]} cycles")
        for index, n, move, total in sorted(results, key=lambda r: -r[1])[: args.top]:
            print(f"    move {index}: {n} instructions; {describe_move(move)}; {total} cycles")
        print(f"  stack: {plan_stack} bytes at most (one plan)")
        profile = probe.call_profiled("probe_plan_bits", *worst[2])
        print(f"  where the worst plan's {worst[1]} instructions run (function, instructions, share):")
        for function, n in profile[: args.functions]:
            print(f"    {n:10} {100 * n / worst[1]:5.1f}%  {function}")

        print(f"  ({time.monotonic() - planning_started:.1f} s)")
        replans: list[int] = []
        if args.replan_moves:
            replans = measure_replans(probe, args.replan_moves, args.top)
        hard: list[int] = []
        if args.hard_moves or args.hard_sub_counts:
            hard = measure_hard(probe, args.hard_moves, args.hard_sub_counts)
        sub_counts: list[int] = []
        if args.sub_count_moves:
            sub_counts = measure_sub_count(probe, args.sub_count_moves, args.top, args.sub_count_seed)
        print("== stepping: probe_step, one call per cycle")
        stepping_started = time.monotonic()
        per_phase: list[list[int]] = [[], [], [], []]
        worst_step = {"instructions": -1}
        stepped_moves = 1
        cycles = step_move(probe, FIXED_STEP_MOVE, 10, per_phase, worst_step)
        step_moves = len(results) if args.step_moves is None else args.step_moves
        for index, _, move, total in results[:step_moves]:
            if total <= args.step_max_cycles:
                cycles += step_move(probe, move, 2, per_phase, worst_step)
                stepped_moves += 1
        print(f"  {stepped_moves} moves, {cycles} cycles: the fixed move ({describe_move(FIXED_STEP_MOVE)}) "
              f"and the random moves of at most {args.step_max_cycles} cycles among the first {step_moves}")
        all_steps = [n for phase in per_phase for n in phase]
        for name, phase in zip(PHASE_NAMES, per_phase):
            if phase:
                print(f"  {name:26} max {max(phase):4}, mean {statistics.fmean(phase):6.1f} instructions "
                      f"({len(phase)} cycles)")
        moving = [n for phase in per_phase[:3] for n in phase]
        print(f"  {'in motion (I-VII)':26} max {max(moving):4}, mean {statistics.fmean(moving):6.1f} instructions "
              f"({len(moving)} cycles)")
        print(f"  {'every cycle':26} max {max(all_steps):4}, mean {statistics.fmean(all_steps):6.1f} instructions "
              f"({len(all_steps)} cycles)")
        print(f"  worst: cycle {worst_step['cycle']} of {worst_step['total']} ({worst_step['phase']}) of "
              f"{describe_move(worst_step['move'])}")
        print(f"  stack: {worst_step['stack']} bytes at most (one step)")
        print(f"  ({time.monotonic() - stepping_started:.1f} s)")
        print(f"== the other generators, one call per cycle (the bench moves and {args.trapezoid_moves} "
              "random trapezoid moves from rest, each to its end)")
        others, setups = measure_other_generators(probe, args.trapezoid_moves)
        stops: list[int] = []
        restarts: list[int] = []
        for name, counts_ in others.items():
            print(f"  {name:26} max {max(counts_):4}, mean {statistics.fmean(counts_):6.1f} instructions "
                  f"({len(counts_)} cycles)")
        print(f"  {'Trapezoid set-up (plans)':26} max {max(setups):4}, mean {statistics.fmean(setups):6.1f} "
              f"instructions ({len(setups)} moves)")
        if args.setup_moves:
            full = measure_setups(probe, full_range_trapezoid_moves(args.setup_moves))
            counts_only = sorted(n for n, _ in full)
            worst_setup = max(full)
            print(f"  {'Trapezoid set-up, whole ranges':26} max {worst_setup[0]}, p99 {percentile(counts_only, 99)}, "
                  f"mean {statistics.fmean(counts_only):.1f} instructions ({len(full)} moves; over 20,000: "
                  f"{sum(1 for n in counts_only if n > 20_000)}; worst {worst_setup[1]}; reported, not budgeted)")
        if args.command_moves:
            print(f"== the trapezoid after commands in motion ({args.command_moves} random moves, one to "
                  "three commands each, every cycle from the first command to the end)")
            within, beyond, commands = measure_trapezoid_commands(probe, args.command_moves)
            others["Trapezoidal after commands"] = within
            print(f"  {'after commands, S <= D':26} max {max(within):4}, mean {statistics.fmean(within):6.1f} "
                  f"instructions ({len(within)} cycles)")
            if beyond:
                # With a starting velocity above D (its landing planned from any state since
                # issue #12's last part): held to the per-step budget too.
                others["Trapezoidal after commands, S > D"] = beyond
                print(f"  {'after commands, S > D':26} max {max(beyond):4}, mean {statistics.fmean(beyond):6.1f} "
                      f"instructions ({len(beyond)} cycles)")
            print(f"  {'the commands (planning)':26} max {max(commands):4}, mean {statistics.fmean(commands):6.1f} "
                  f"instructions ({len(commands)} commands)")
            scurve_after, abrupt_after, velocity_after, stops, restarts = measure_other_commands(
                probe, args.command_moves)
            others["VelocityContouring after commands"] = velocity_after
            others["SCurve after smooth stops"] = scurve_after
            print(f"  {'SCurve after smooth stops':26} max {max(scurve_after):4}, mean "
                  f"{statistics.fmean(scurve_after):6.1f} instructions ({len(scurve_after)} cycles)")
            # The abrupt stop's two cycles (the drop, the level-off) are replayed by the fast
            # path since issue #12's last part: held to the per-step budget too.
            others["SCurve after abrupt stops"] = abrupt_after
            print(f"  {'SCurve after abrupt stops':26} max {max(abrupt_after):4}, mean "
                  f"{statistics.fmean(abrupt_after):6.1f} instructions ({len(abrupt_after)} cycles)")
            print(f"  {'SCurve stop commands':26} max {max(stops):4}, mean "
                  f"{statistics.fmean(stops):6.1f} instructions ({len(stops)} stops)")
            print(f"  {'SCurve restarts (plans)':26} max {max(restarts):4}, mean "
                  f"{statistics.fmean(restarts):6.1f} instructions ({len(restarts)} restarts)")
            print(f"  {'VelocityContouring after commands':26} max {max(velocity_after):4}, mean "
                  f"{statistics.fmean(velocity_after):6.1f} instructions ({len(velocity_after)} cycles)")
        print(f"== a 3-axis linear interpolation, one call per cycle (LinearInterpolation::step: the "
              f"profile plus the geometry; the manual's line and {args.line_moves} random lines per profile)")
        lines_started = time.monotonic()
        # The crate's S-curve drives the fixed move's and the stepped random moves' registers.
        scurve_moves = [FIXED_STEP_MOVE] + [move for _, _, move, total in results[:args.line_moves * 4]
                                            if total <= args.step_max_cycles][:args.line_moves]
        lines = measure_lines(probe, args.line_moves, scurve_moves)
        for name, counts_ in lines.items():
            print(f"  {'3-axis line, ' + name:26} max {max(counts_):4}, mean {statistics.fmean(counts_):6.1f} "
                  f"instructions ({len(counts_)} cycles)")
        # The same drives without the geometry: the MCX514 profiles as one-axis generators, held
        # to SPEC §16's 40 per cycle with the others (their cycles laid out as runs, #12, #14).
        measured_alone = measure_mcx514_axis(probe, args.line_moves)
        for profile, name in (("mcx514", "Mcx514Trapezoidal"), ("mcx514_scurve", "Mcx514SCurve")):
            alone, axis_setups = measured_alone[profile]
            others[f"{name} alone"] = alone
            print(f"  {name + ' alone':26} max {max(alone):4}, mean {statistics.fmean(alone):6.1f} "
                  f"instructions ({len(alone)} cycles)")
            print(f"  {name + ' set-up':26} max {max(axis_setups):4}, mean "
                  f"{statistics.fmean(axis_setups):6.1f} instructions ({len(axis_setups)} moves: the "
                  "registers converted from pps with f64 arithmetic, emulated on this core, and the "
                  "plan; reported)")
        mcx514_plans = measure_mcx514_plans(probe, args.mcx514_plan_moves) if args.mcx514_plan_moves else []
        if mcx514_plans:
            ordered = sorted(mcx514_plans)
            print(f"  {'Mcx514SCurve plan':26} max {ordered[-1]:5}, p99 {ordered[len(ordered) * 99 // 100]:5}, "
                  f"mean {statistics.fmean(ordered):7.1f} instructions ({len(ordered)} moves over the whole "
                  "register ranges: Layout::lay_out and its callees)")
        print(f"  ({time.monotonic() - lines_started:.1f} s)")
        print(f"== MCX514 circular interpolation, one call per cycle (profile and arc; the manual's "
              f"circle and {args.circle_moves} random ones, each to its end)")
        circles = measure_circles(probe, args.circle_moves)
        for name, counts_ in circles.items():
            print(f"  {'circle, ' + name:26} max {max(counts_):4}, mean {statistics.fmean(counts_):6.1f} "
                  f"instructions ({len(counts_)} cycles)")
    except ProbeFailure as failure:
        print(f"error: the probe failed: {failure}", file=sys.stderr)
        return 2
    print(f"== {time.monotonic() - started:.1f} s in all")

    def within(what: str, values: list[int], budget: int | None, where: str, unit: str) -> bool:
        """Prints whether the largest of `values` is within `budget` (no budget: nothing to say)."""
        if budget is not None and not values:
            print(f"FAIL: {what}: nothing measured for its budget of {budget}", file=sys.stderr)
            return False
        if budget is None:
            return True
        worst_value = max(values)
        if worst_value > budget:
            over = sum(1 for n in values if n > budget)
            print(f"FAIL: {what} executes up to {worst_value} instructions{where}, over the budget of "
                  f"{budget} (SPEC §16) in {over} of {len(values)} {unit}", file=sys.stderr)
            return False
        print(f"ok: {what} within {budget} instructions (worst {worst_value})")
        return True

    planning_ok = within("planning", counts, args.plan_budget, f" (move {worst[0]})", "moves")
    if hard:
        planning_ok &= within("planning the surveys' costliest moves", hard, args.plan_budget, "", "moves")
    planning_ok &= within("Trapezoid set-up", setups, args.setup_budget, "", "moves")
    planning_ok &= within("an S-curve stop command", stops, args.stop_budget, "", "stops")
    # A restart plans a move: the planning budget, wherever restarts were measured.
    if restarts:
        planning_ok &= within("an S-curve restart (a plan)", restarts, args.plan_budget, "", "restarts")
    planning_ok &= within("the MCX514 S-curve's plan", mcx514_plans, args.mcx514_plan_budget, "", "moves")
    planning_ok &= within("planning in place (set_parameters)", replans, args.replan_budget, "", "moves")
    stepping_ok = within("one step of SCurve", all_steps, args.step_budget, "", "cycles")
    for name, counts_ in others.items():
        stepping_ok &= within(f"one step of {name}", counts_, args.step_budget, "", "cycles")
    lines_ok = True
    for name, counts_ in lines.items():
        lines_ok &= within(f"one cycle of a 3-axis line driven by {name}", counts_, line_budgets.get(name), "",
                           "cycles")
    circle_budgets: dict[str, int] = {}
    for budget in args.circle_budget:
        name, _, value = budget.partition("=")
        circle_budgets[name] = int(value)
    circles_ok = True
    for name, counts_ in circles.items():
        circles_ok &= within(f"one cycle of a circle driven by {name}", counts_, circle_budgets.get(name), "",
                             "cycles")
    sub_count_ok = True
    if args.sub_count_ceiling is not None:
        if not sub_counts:
            print("FAIL: --sub-count-ceiling without --sub-count-moves", file=sys.stderr)
            sub_count_ok = False
        elif max(sub_counts) > args.sub_count_ceiling:
            print(f"FAIL: planning from fractional positions executes up to {max(sub_counts)} "
                  f"instructions, over its ceiling of {args.sub_count_ceiling} (SPEC §16's budget is "
                  f"20,000; CI holds this sample to it, issue #11)", file=sys.stderr)
            sub_count_ok = False
        else:
            over = sum(1 for n in sub_counts if n > 20_000)
            print(f"ok: planning from fractional positions within its ceiling of {args.sub_count_ceiling} "
                  f"(worst {max(sub_counts)}; {over} of {len(sub_counts)} over SPEC §16's 20,000, issue #11)")
    status = 0 if planning_ok and stepping_ok and lines_ok and circles_ok and sub_count_ok else 1
    return status


if __name__ == "__main__":
    sys.exit(main())

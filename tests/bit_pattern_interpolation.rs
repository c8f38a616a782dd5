//! SPEC §12.5, bit patterns: per-axis "+"/"−" words of 16 steps, LSB first, both bits set ending
//! the data, paced by the MCX514 trapezoid. The reference expands every bit, step by step, in
//! the test; the interpolation must agree with it on every cycle.

use profilegen::conformance::{check_identities, check_limits};
use profilegen::format::mcx514::{
    Acceleration, Deceleration, DriveSpeed, InitialSpeed, ManualDecelerationPoint,
};
use profilegen::format::CycleTime;
use profilegen::interpolation::{BitPatternInterpolation, BitWord, ContinuousDriving};
use profilegen::{Error, ProfileGenerator, StopKind};
use proptest::prelude::*;

fn driving(initial: u32, drive: u32, rate: u32) -> ContinuousDriving {
    ContinuousDriving {
        initial_speed: InitialSpeed::from_bits(initial).unwrap(),
        drive_speed: DriveSpeed::from_bits(drive).unwrap(),
        acceleration: Acceleration::from_bits(rate).unwrap(),
        deceleration: Deceleration::from_bits(rate).unwrap(),
    }
}

/// Every axis after every step, bit by bit, up to the end of the data: the reference.
fn expand<const N: usize>(words: &[[BitWord; N]]) -> Vec<[i32; N]> {
    let mut positions = vec![[0; N]];
    for group in words {
        for bit in 0..16 {
            if group
                .iter()
                .any(|w| (w.plus >> bit) & (w.minus >> bit) & 1 == 1)
            {
                return positions;
            }
            let mut next = *positions.last().unwrap();
            for (axis, word) in group.iter().enumerate() {
                next[axis] +=
                    i32::from((word.plus >> bit) & 1) - i32::from((word.minus >> bit) & 1);
            }
            positions.push(next);
        }
    }
    positions
}

/// Runs `words` (refilling as room appears) and compares every cycle with the reference.
fn run_against_reference<const N: usize>(
    words: &[[BitWord; N]],
    driving: ContinuousDriving,
    point: Option<u32>,
) -> u64 {
    let reference = expand(words);
    let point = point.map(|p| ManualDecelerationPoint::from_bits(p).unwrap());
    let cycle = CycleTime::from_seconds(1e-3).unwrap();
    let mut run = BitPatternInterpolation::<N>::new(driving, point, cycle).unwrap();
    let mut pushed = 0;
    let refill = |run: &mut BitPatternInterpolation<N>, pushed: &mut usize| {
        while run.free() > 0 && *pushed < words.len() {
            if run.push(words[*pushed]).is_err() {
                break; // after the end of the data
            }
            *pushed += 1;
        }
    };
    refill(&mut run, &mut pushed);
    let mut before = run.state();
    let mut cycles = 0;
    while !run.is_complete() {
        let after = run.step();
        check_identities(&before.driving, &after.driving).unwrap();
        check_limits(&before.driving, &after.driving, &run.profile().limits()).unwrap();
        assert_eq!(
            after.axes, reference[after.step as usize],
            "step {}",
            after.step
        );
        refill(&mut run, &mut pushed);
        before = after;
        cycles += 1;
        assert!(cycles < 100_000);
    }
    assert_eq!(
        before.step as usize,
        reference.len() - 1,
        "the run ends at the end of the data"
    );
    before.step
}

#[test]
fn the_end_of_data_and_the_full_buffer() {
    let cycle = CycleTime::from_seconds(1e-3).unwrap();
    let mut run = BitPatternInterpolation::<3>::new(driving(3_000, 3_000, 1), None, cycle).unwrap();
    let word = [
        BitWord::new(0xAAAA, 0x5555),
        BitWord::new(0xFFFF, 0),
        BitWord::new(0, 1),
    ];
    for _ in 0..8 {
        run.push(word).unwrap();
    }
    assert_eq!(run.free(), 0);
    assert!(matches!(
        run.push(word),
        Err(Error::Refused {
            parameter: "bit pattern",
            ..
        })
    ));
    // Three steps per cycle: after 6 cycles, 18 steps: a word and 2 steps.
    let mut state = run.state();
    for _ in 0..6 {
        state = run.step();
    }
    assert_eq!(state.step, 18);
    // X: +−+− … nets 0 per word, then −, + (bit 16 = bit 0: minus, bit 1: plus): 0.
    // Y: 18 forward; Z: one back at bit 0 of each word: −2.
    assert_eq!(state.axes, [0, 18, -2]);
    assert_eq!(run.free(), 1);
    // Both bits of Y's step 5 set: the data ends after 5 more steps of that word.
    run.push([
        BitWord::default(),
        BitWord::new(1 << 5, 1 << 5),
        BitWord::default(),
    ])
    .unwrap();
    assert!(matches!(
        run.push(word),
        Err(Error::Refused {
            parameter: "bit pattern",
            ..
        })
    ));
    while !run.is_complete() {
        state = run.step();
    }
    assert_eq!(state.step, 8 * 16 + 5);
    assert_eq!(state.axes, [0, 8 * 16, -8]);
}

#[test]
fn the_manual_deceleration_point_and_a_stop() {
    // 20 words of X forward, end of data after 320 steps; SV 2, DV 10, 1 pulse/cycle² at 1 ms.
    let mut words = vec![[BitWord::new(0xFFFF, 0)]; 20];
    words.push([BitWord::new(1, 1)]);
    let steps = run_against_reference(&words, driving(2_000, 10_000, 1_000_000), Some(280));
    assert_eq!(steps, 320);
    // A stop: nothing more can be buffered, the axes stay with the steps.
    let cycle = CycleTime::from_seconds(1e-3).unwrap();
    let mut run =
        BitPatternInterpolation::<1>::new(driving(2_000, 10_000, 1_000_000), None, cycle).unwrap();
    for _ in 0..8 {
        run.push([BitWord::new(0xFFFF, 0)]).unwrap();
    }
    for _ in 0..5 {
        run.step();
    }
    run.stop(StopKind::Abrupt);
    let held = run.step();
    assert_eq!(run.step().axes, held.axes);
    assert!(run.push([BitWord::new(0xFFFF, 0)]).is_err());
}

fn word() -> impl Strategy<Value = BitWord> {
    // Mostly disjoint halves; the end of data comes from an explicit both-set bit.
    (any::<u16>(), any::<u16>())
        .prop_map(|(plus, minus)| BitWord::new(plus & !minus, minus & !plus))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn every_cycle_matches_the_bit_by_bit_reference(
        words in prop::collection::vec([word(), word()], 1..40),
        end in prop::option::of(0u32..16),
        speed in 1_000u32..60_000,
        rate in 100_000u32..5_000_000,
    ) {
        let mut words = words;
        if let Some(bit) = end {
            words.push([BitWord::new(1 << bit, 1 << bit), BitWord::default()]);
        }
        let total = expand(&words).len() as u32 - 1;
        let point = total.saturating_sub(speed / 1_000 * 4);
        run_against_reference(&words, driving(1_000.min(speed), speed, rate), Some(point));
    }
}

//! Mutated copies of the shipped STEP exports through the reader: random byte flips, cuts,
//! deleted, duplicated and swapped lines, changed numbers and references. Every case must end
//! in `Ok` (then every solid is validated and its tolerance finite) or a typed `Err`, never a
//! panic, within a bounded time. Deterministic: a seeded SplitMix64.

use geom_param::step::read_step;
use std::time::{Duration, Instant};

/// SplitMix64 (Steele, Lea, Flood 2014).
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
}

fn fixture(name: &str) -> Vec<u8> {
    let path = format!("{}/../../fixtures/step/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// One random edit of `text`.
fn mutate(text: &[u8], rng: &mut SplitMix64) -> Vec<u8> {
    let mut out = text.to_vec();
    let lines: Vec<&[u8]> = text.split(|&b| b == b'\n').collect();
    match rng.below(8) {
        // Flip a byte to anything.
        0 => {
            let at = rng.below(out.len());
            out[at] = (rng.next_u64() & 0xff) as u8;
        }
        // Cut.
        1 => out.truncate(rng.below(out.len())),
        // Delete a line.
        2 => {
            let k = rng.below(lines.len());
            out = lines
                .iter()
                .enumerate()
                .filter(|&(i, _)| i != k)
                .flat_map(|(_, l)| l.iter().copied().chain([b'\n']))
                .collect();
        }
        // Duplicate a line (a duplicate id, or a second header entity).
        3 => {
            let k = rng.below(lines.len());
            out = lines
                .iter()
                .enumerate()
                .flat_map(|(i, l)| {
                    let times = if i == k { 2 } else { 1 };
                    std::iter::repeat_n(l.iter().copied().chain([b'\n']), times).flatten()
                })
                .collect();
        }
        // Swap two lines' bodies after '=' (an entity of the wrong type where one is needed).
        4 => {
            let (a, b) = (rng.below(lines.len()), rng.below(lines.len()));
            let body = |l: &[u8]| l.iter().position(|&c| c == b'=').map(|p| l[p..].to_vec());
            let (ba, bb) = (body(lines[a]), body(lines[b]));
            out = lines
                .iter()
                .enumerate()
                .flat_map(|(i, l)| {
                    let mut line = l.to_vec();
                    if let (Some(ba), Some(bb)) = (&ba, &bb) {
                        let head =
                            |l: &[u8]| l[..l.iter().position(|&c| c == b'=').unwrap_or(0)].to_vec();
                        if i == a {
                            line = [head(l), bb.clone()].concat();
                        }
                        if i == b {
                            line = [head(l), ba.clone()].concat();
                        }
                    }
                    line.into_iter().chain([b'\n'])
                })
                .collect();
        }
        // Change a digit (a coordinate, a radius, a reference, a multiplicity).
        5 | 6 => {
            let digits: Vec<usize> = (0..out.len())
                .filter(|&i| out[i].is_ascii_digit())
                .collect();
            if !digits.is_empty() {
                let at = digits[rng.below(digits.len())];
                out[at] = b'0' + (rng.below(10) as u8);
            }
        }
        // Flip an orientation flag.
        _ => {
            let flags: Vec<usize> = (0..out.len().saturating_sub(2))
                .filter(|&i| {
                    out[i] == b'.'
                        && (out[i + 1] == b'T' || out[i + 1] == b'F')
                        && out[i + 2] == b'.'
                })
                .collect();
            if !flags.is_empty() {
                let at = flags[rng.below(flags.len())] + 1;
                out[at] = if out[at] == b'T' { b'F' } else { b'T' };
            }
        }
    }
    out
}

fn run_mutations(name: &str, cases: usize, seed: u64) {
    let text = fixture(name);
    let mut rng = SplitMix64(seed);
    let (mut ok, mut errors) = (0, 0);
    let mut slowest = Duration::ZERO;
    for case in 0..cases {
        let mutated = mutate(&text, &mut rng);
        let start = Instant::now();
        match read_step(&mutated) {
            Ok(solids) => {
                ok += 1;
                for s in &solids {
                    assert!(
                        s.solid.tolerance.is_finite() && s.solid.tolerance > 0.0,
                        "{name} case {case}"
                    );
                    geom_param::validate(&s.solid)
                        .unwrap_or_else(|e| panic!("{name} case {case}: {e}"));
                }
            }
            Err(e) => {
                errors += 1;
                assert!(!e.to_string().is_empty());
            }
        }
        slowest = slowest.max(start.elapsed());
    }
    println!("{name}: {ok} read, {errors} refused, slowest {slowest:?}");
    assert!(
        errors > 0 && ok > 0,
        "{name}: the mutations exercise both outcomes"
    );
    assert!(
        slowest < Duration::from_secs(20),
        "{name}: a mutated file took {slowest:?}"
    );
}

#[test]
fn mutated_cube_and_cylinder() {
    run_mutations("red_cube_blue_cylinder.step", 400, 14);
}

#[test]
fn mutated_solidworks_base_interface() {
    run_mutations("solidworks_base_interface.step", 200, 1414);
}

#[test]
fn random_bytes() {
    let mut rng = SplitMix64(7);
    for _ in 0..200 {
        let n = rng.below(4096);
        let mut bytes: Vec<u8> = (0..n).map(|_| (rng.next_u64() & 0xff) as u8).collect();
        if rng.below(2) == 0 {
            let header = b"ISO-10303-21;\nHEADER;\n";
            bytes.splice(0..0, header.iter().copied());
        }
        assert!(read_step(&bytes).is_err());
    }
}

//! Bad input through the object loader: random bytes, random JSON, mutated copies of the fixture
//! objects and profiles with non-finite or denormal coordinates built in code. Every case must
//! end in `Ok` or a typed `Err` (a panic fails the test), and every model that builds must have
//! finite mesh positions, normals and chordal error. Deterministic: a seeded SplitMix64.
#![cfg(feature = "json")]

use geom_param::{MeshOptions, ObjectDescription, ObjectFile, ObjectModel, Profile, SegmentSpec};
use serde_json::Value;
use std::path::Path;
use std::time::{Duration, Instant};

/// SplitMix64 (Steele, Lea, Flood 2014): small, seedable, good enough to pick cases.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in 0..n (n > 0).
    fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

const OPTIONS: MeshOptions = MeshOptions {
    chordal_tolerance: 0.5,
};

/// Counts of what happened, printed at the end of each test.
#[derive(Default, Debug)]
struct Tally {
    cases: usize,
    parse_errors: usize,
    build_errors: usize,
    built: usize,
    slowest: Duration,
}

/// Asserts that a built model holds no NaN (or infinity) in its meshes.
fn check_model(model: &ObjectModel, what: &str) {
    for (c, mesh) in model.meshes.iter().enumerate() {
        assert!(
            mesh.chordal_error.is_finite(),
            "{what}: component {c} chordal_error {}",
            mesh.chordal_error
        );
        for (i, p) in mesh.positions.iter().enumerate() {
            assert!(p.is_finite(), "{what}: component {c} position {i} = {p}");
        }
        for (i, n) in mesh.normals.iter().enumerate() {
            assert!(n.is_finite(), "{what}: component {c} normal {i} = {n}");
        }
    }
}

/// Loads and (if it parses) builds `text`; a panic anywhere fails the test.
fn load(text: &str, tally: &mut Tally, what: &str) {
    tally.cases += 1;
    if std::env::var_os("ROBUST_TRACE").is_some() {
        eprintln!("CASE {what}");
    }
    let Ok(description) = ObjectDescription::from_json(text) else {
        tally.parse_errors += 1;
        return;
    };
    build(&description.profile, tally, what);
}

fn build(specs: &[SegmentSpec], tally: &mut Tally, what: &str) {
    let start = Instant::now();
    let result = Profile::new(specs)
        .map_err(|_| ())
        .and_then(|p| ObjectModel::from_profile("case", p, &OPTIONS).map_err(|_| ()));
    tally.slowest = tally.slowest.max(start.elapsed());
    if std::env::var_os("ROBUST_TRACE").is_some() {
        eprintln!("TIME {:?} {what}", start.elapsed());
    }
    match result {
        Ok(model) => {
            tally.built += 1;
            check_model(&model, what);
        }
        Err(()) => tally.build_errors += 1,
    }
}

/// Whether the object file at `path` is a solid of revolution (a top-level `profile`).
fn is_revolved(path: &Path) -> bool {
    std::fs::read_to_string(path)
        .ok()
        .and_then(|t| serde_json::from_str::<Value>(&t).ok())
        .is_some_and(|v| v.get("profile").is_some())
}

fn fixture_texts() -> Vec<(String, String)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/objects");
    let mut out = Vec::new();
    for entry in std::fs::read_dir(&dir).expect("fixtures/objects") {
        let path = entry.expect("entry").path();
        // The general (builder) objects are fuzzed on their own below.
        if path.extension().is_some_and(|e| e == "json") && is_revolved(&path) {
            let name = path
                .file_stem()
                .expect("stem")
                .to_string_lossy()
                .into_owned();
            out.push((name, std::fs::read_to_string(&path).expect("fixture")));
        }
    }
    out.sort();
    assert_eq!(out.len(), 6, "the six paper objects");
    out
}

// ---------------------------------------------------------------------------------------------
// Random bytes and random JSON.

/// Number literals at the edges of what JSON and f64 can hold, as text.
const NUMBER_TEXTS: &[&str] = &[
    "0",
    "-0.0",
    "1",
    "-1",
    "3.5",
    "1e300",
    "-1e300",
    "1.7976931348623157e308",
    "5e-324",
    "-5e-324",
    "2.2250738585072014e-308",
    "1e-9",
    "-1e-9",
    "1e400",
    "-1e400",
    "1e-400",
    "1e99999999999999999999",
    "123456789012345678901234567890",
    "-9223372036854775809",
    "18446744073709551616",
    "0.1e1",
    "1E+2",
];

const KEYS: &[&str] = &[
    "name", "note", "profile", "line", "arc", "bezier", "from", "to", "center", "ccw", "points",
    "", "x", "é", "\\u0000",
];

fn random_json(rng: &mut SplitMix64, depth: u32, out: &mut String) {
    let choice = if depth == 0 {
        rng.below(5)
    } else {
        rng.below(8)
    };
    match choice {
        0 => out.push_str(rng.pick::<&str>(NUMBER_TEXTS)),
        1 => out.push_str(rng.pick::<&str>(&["true", "false", "null"])),
        2 => {
            out.push('"');
            out.push_str(rng.pick::<&str>(KEYS));
            out.push('"');
        }
        3 => out.push_str(&format!("{:?}", (rng.unit() - 0.5) * 200.0)),
        4 => out.push_str(&format!(
            "[{}, {}]",
            rng.pick(NUMBER_TEXTS),
            rng.pick(NUMBER_TEXTS)
        )),
        5 | 6 => {
            out.push('{');
            for i in 0..rng.below(5) {
                if i > 0 {
                    out.push(',');
                }
                out.push('"');
                out.push_str(rng.pick::<&str>(KEYS));
                out.push_str("\":");
                random_json(rng, depth - 1, out);
            }
            out.push('}');
        }
        _ => {
            out.push('[');
            for i in 0..rng.below(5) {
                if i > 0 {
                    out.push(',');
                }
                random_json(rng, depth - 1, out);
            }
            out.push(']');
        }
    }
}

/// A profile of 0..6 random segments, each coordinate an edge-case literal or a plain number.
fn random_object(rng: &mut SplitMix64) -> String {
    let num = |rng: &mut SplitMix64| -> String {
        if rng.below(3) == 0 {
            rng.pick(NUMBER_TEXTS).to_string()
        } else {
            format!("{:?}", (rng.unit() * 40.0).round() / 4.0)
        }
    };
    let mut segments = Vec::new();
    for _ in 0..rng.below(7) {
        let pt = |rng: &mut SplitMix64| format!("[{}, {}]", num(rng), num(rng));
        segments.push(match rng.below(3) {
            0 => format!(r#"{{"line": {{"from": {}, "to": {}}}}}"#, pt(rng), pt(rng)),
            1 => format!(
                r#"{{"arc": {{"center": {}, "from": {}, "to": {}, "ccw": {}}}}}"#,
                pt(rng),
                pt(rng),
                pt(rng),
                rng.below(2) == 0
            ),
            _ => format!(
                r#"{{"bezier": {{"points": [{}, {}, {}, {}]}}}}"#,
                pt(rng),
                pt(rng),
                pt(rng),
                pt(rng)
            ),
        });
    }
    format!(
        r#"{{"name": "random", "profile": [{}]}}"#,
        segments.join(", ")
    )
}

#[test]
fn random_bytes_and_random_json_never_panic() {
    let mut rng = SplitMix64(0x000B_1EC7_10AD);
    let mut tally = Tally::default();
    // Raw bytes (lossily decoded) and bytes from the JSON alphabet.
    const ALPHABET: &[u8] = b"{}[]\",:0123456789.eE+-truefalsnl \n\\u";
    for case in 0..3000 {
        let len = rng.below(96);
        let bytes: Vec<u8> = if case % 2 == 0 {
            (0..len).map(|_| rng.next_u64() as u8).collect()
        } else {
            (0..len).map(|_| *rng.pick(ALPHABET)).collect()
        };
        load(&String::from_utf8_lossy(&bytes), &mut tally, "random bytes");
    }
    // Deeply nested brackets: the parser's recursion limit, not the stack, must stop them.
    for depth in [127, 128, 129, 10_000] {
        load(&"[".repeat(depth), &mut tally, "deep arrays");
        load(&"{\"a\":".repeat(depth), &mut tally, "deep objects");
    }
    // Random JSON values of any shape.
    for _ in 0..3000 {
        let mut text = String::new();
        random_json(&mut rng, 4, &mut text);
        load(&text, &mut tally, &text.clone());
    }
    // Well-formed objects with random profiles.
    for _ in 0..1500 {
        let text = random_object(&mut rng);
        load(&text, &mut tally, &text.clone());
    }
    println!("{tally:?}");
    assert_eq!(tally.cases, 7508);
}

// ---------------------------------------------------------------------------------------------
// Mutated fixtures.

/// The numbers of a segment's points, as mutable JSON values.
fn points_of(segment: &mut Value) -> Vec<&mut Value> {
    let mut out = Vec::new();
    if let Some(Value::Object(body)) = segment.as_object_mut().and_then(|m| m.values_mut().next()) {
        for (key, v) in body.iter_mut() {
            match (key.as_str(), v) {
                ("points", Value::Array(list)) => out.extend(list.iter_mut()),
                ("from" | "to" | "center", v) => out.push(v),
                _ => {}
            }
        }
    }
    out
}

fn coordinates_of(segment: &mut Value) -> Vec<&mut Value> {
    points_of(segment)
        .into_iter()
        .filter_map(|p| p.as_array_mut())
        .flat_map(|p| p.iter_mut())
        .collect()
}

fn num(v: f64) -> Value {
    serde_json::Number::from_f64(v).map_or(Value::Null, Value::Number)
}

/// One random mutation of a profile (a JSON array of segments); returns its name.
fn mutate(rng: &mut SplitMix64, profile: &mut Vec<Value>) -> &'static str {
    if profile.is_empty() {
        return "empty";
    }
    let n = profile.len();
    let i = rng.below(n);
    match rng.below(14) {
        0 => {
            profile.remove(i);
            "delete segment"
        }
        1 => {
            let s = profile[i].clone();
            profile.insert(i, s);
            "duplicate segment"
        }
        2 => {
            profile.swap(i, rng.below(n));
            "swap segments"
        }
        3 => {
            let mut cs = coordinates_of(&mut profile[i]);
            if !cs.is_empty() {
                let k = rng.below(cs.len());
                let x = cs[k].as_f64().unwrap_or(0.0);
                let eps = 10f64.powf(-16.0 + 10.0 * rng.unit())
                    * if rng.below(2) == 0 { 1.0 } else { -1.0 };
                *cs[k] = num(x + eps * x.abs().max(1.0));
            }
            "tiny perturbation"
        }
        4 => {
            let mut cs = coordinates_of(&mut profile[i]);
            if !cs.is_empty() {
                let k = rng.below(cs.len());
                let x = cs[k].as_f64().unwrap_or(0.0);
                let big =
                    10f64.powf(3.0 + 9.0 * rng.unit()) * if rng.below(2) == 0 { 1.0 } else { -1.0 };
                *cs[k] = num(x + big);
            }
            "huge perturbation"
        }
        5 => {
            if let Some(Value::Object(arc)) = profile[i].get_mut("arc") {
                let ccw = arc.get("ccw").and_then(Value::as_bool).unwrap_or(true);
                arc.insert("ccw".into(), Value::Bool(!ccw));
            }
            "flip ccw"
        }
        6 => {
            let mut cs = coordinates_of(&mut profile[i]);
            if !cs.is_empty() {
                let k = rng.below(cs.len());
                *cs[k] = num(-1e-9);
            }
            "coordinate -1e-9"
        }
        7 => {
            if let Some(Value::Object(arc)) = profile[i].get_mut("arc") {
                let from = arc.get("from").cloned().unwrap_or(Value::Null);
                let key = *rng.pick(&["to", "center"]);
                arc.insert(key.into(), from);
            }
            "collapse arc"
        }
        8 => {
            // Move the vertex shared by segments i and i + 1 onto another segment's point (or
            // a random point): the profile stays closed but may touch or cross itself.
            let j = (i + 1) % n;
            let target = {
                let k = rng.below(n);
                let ps = points_of(&mut profile[k]);
                if ps.is_empty() || rng.below(4) == 0 {
                    Value::Array(vec![num(rng.unit() * 50.0), num(rng.unit() * 180.0)])
                } else {
                    let m = rng.below(ps.len());
                    ps[m].clone()
                }
            };
            set_end(&mut profile[i], "to", &target);
            set_end(&mut profile[j], "from", &target);
            "move shared vertex"
        }
        9 => {
            profile.remove(n - 1);
            "open (drop last)"
        }
        10 => {
            let mut cs = coordinates_of(&mut profile[i]);
            if !cs.is_empty() {
                let k = rng.below(cs.len());
                *cs[k] = rng
                    .pick(&[
                        Value::Null,
                        Value::String("1".into()),
                        Value::Bool(true),
                        num(1e300),
                        num(-1e300),
                        num(5e-324),
                        num(-0.0),
                        num(f64::MAX),
                        Value::Array(vec![]),
                    ])
                    .clone();
            }
            "odd value"
        }
        11 => {
            // Reverse one segment: a gap at both of its ends (or a closed path the wrong way).
            if let Some(Value::Object(body)) = profile[i]
                .as_object_mut()
                .and_then(|m| m.values_mut().next())
            {
                let from = body.get("from").cloned();
                let to = body.get("to").cloned();
                if let (Some(f), Some(t)) = (from, to) {
                    body.insert("from".into(), t);
                    body.insert("to".into(), f);
                }
                if let Some(Value::Array(points)) = body.get_mut("points") {
                    points.reverse();
                }
            }
            "reverse segment"
        }
        12 => {
            // Reverse the whole profile (clockwise around the material).
            profile.reverse();
            for s in profile.iter_mut() {
                if let Some(Value::Object(body)) =
                    s.as_object_mut().and_then(|m| m.values_mut().next())
                {
                    let from = body.get("from").cloned();
                    let to = body.get("to").cloned();
                    if let (Some(f), Some(t)) = (from, to) {
                        body.insert("from".into(), t);
                        body.insert("to".into(), f);
                    }
                    if let Some(arc_ccw) = body.get("ccw").and_then(Value::as_bool) {
                        body.insert("ccw".into(), Value::Bool(!arc_ccw));
                    }
                    if let Some(Value::Array(points)) = body.get_mut("points") {
                        points.reverse();
                    }
                }
            }
            "reverse profile"
        }
        _ => {
            // Scale the whole object: tiny or huge objects against the fixed 0.5 mm tolerance.
            // (1e3 is left out: see `jar_scaled_by_1000_builds_in_bounded_time`.)
            let factor = *rng.pick(&[1e-9, 1e-3, 10.0, 1e6, 1e12, -1.0]);
            for s in profile.iter_mut() {
                for c in coordinates_of(s) {
                    if let Some(x) = c.as_f64() {
                        *c = num(x * factor);
                    }
                }
            }
            "scale object"
        }
    }
}

fn set_end(segment: &mut Value, key: &str, point: &Value) {
    if let Some(Value::Object(body)) = segment.as_object_mut().and_then(|m| m.values_mut().next()) {
        if body.contains_key(key) {
            body.insert(key.into(), point.clone());
        } else if let Some(Value::Array(points)) = body.get_mut("points") {
            let idx = if key == "from" {
                0
            } else {
                points.len().saturating_sub(1)
            };
            if let Some(p) = points.get_mut(idx) {
                *p = point.clone();
            }
        }
    }
}

#[test]
fn mutated_fixtures_never_panic() {
    let mut rng = SplitMix64(0xF1C7_0BE5);
    let mut tally = Tally::default();
    let mut by_mutation: std::collections::BTreeMap<&str, usize> = Default::default();
    for (name, text) in fixture_texts() {
        let original: Value = serde_json::from_str(&text).expect("fixture JSON");
        for _ in 0..120 {
            let mut value = original.clone();
            let Some(Value::Array(profile)) = value.get_mut("profile") else {
                panic!("{name}: no profile");
            };
            let mut applied = Vec::new();
            for _ in 0..1 + rng.below(3) {
                let m = mutate(&mut rng, profile);
                *by_mutation.entry(m).or_default() += 1;
                applied.push(m);
            }
            let mutated = serde_json::to_string(&value).expect("serialise");
            load(
                &mutated,
                &mut tally,
                &format!("{name} after {applied:?}: {mutated}"),
            );
        }
    }
    println!("{tally:?}\n{by_mutation:?}");
    assert_eq!(tally.cases, 720);
}

// ---------------------------------------------------------------------------------------------
// Non-finite and denormal coordinates in code.

fn coordinates_mut(s: &mut SegmentSpec) -> Vec<&mut f64> {
    match s {
        SegmentSpec::Line { from, to } => from.iter_mut().chain(to.iter_mut()).collect(),
        SegmentSpec::Arc {
            center, from, to, ..
        } => center
            .iter_mut()
            .chain(from.iter_mut())
            .chain(to.iter_mut())
            .collect(),
        SegmentSpec::Bezier { points } => points.iter_mut().flat_map(|p| p.iter_mut()).collect(),
    }
}

#[test]
fn non_finite_and_denormal_coordinates_in_code_never_panic() {
    const VALUES: [f64; 8] = [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        5e-324,
        -5e-324,
        f64::MIN_POSITIVE,
        1e308,
        -0.0,
    ];
    let mut tally = Tally::default();
    for (name, text) in fixture_texts() {
        let specs = ObjectDescription::from_json(&text)
            .expect("fixture")
            .profile;
        for s in 0..specs.len() {
            let slots = coordinates_mut(&mut specs[s].clone()).len();
            for k in 0..slots {
                for value in VALUES {
                    let mut case = specs.clone();
                    *coordinates_mut(&mut case[s])[k] = value;
                    tally.cases += 1;
                    build(
                        &case,
                        &mut tally,
                        &format!("{name}: segment {s} coordinate {k} = {value:e}"),
                    );
                }
            }
        }
        // Every coordinate at once.
        for value in VALUES {
            let mut case = specs.clone();
            for seg in &mut case {
                for c in coordinates_mut(seg) {
                    *c = value;
                }
            }
            tally.cases += 1;
            build(
                &case,
                &mut tally,
                &format!("{name}: all coordinates {value:e}"),
            );
        }
    }
    println!("{tally:?}");
    assert!(tally.cases > 500);
}

// ---------------------------------------------------------------------------------------------
// Findings kept as regressions with their literal inputs.

/// FIXME (found by `mutated_fixtures_never_panic`, seed 0xF1C7_0BE5, mutation "scale object"):
/// the jar scaled by 1000 (91 m tall) at a 0.5 mm chordal tolerance is inside the accepted range
/// (it was accepted when the bound was 1e-7 x size; now it is refused by the 2e-5 x size bound) but meshes into hundreds of thousands of vertices, and the convex
/// hull of a component (parry `try_convex_hull`, from `ConvexHull::of_mesh`) then takes 19 s in
/// one run and more than 10 minutes in another (hash-order dependent). Expected: the build ends
/// (Ok or a typed error such as a mesh-size limit) within a few seconds.
#[test]
fn jar_scaled_by_1000_builds_in_bounded_time() {
    const JAR_X1000: &str = r#"{"name":"jar","profile":[{"line":{"from":[0.0,0.0],"to":[30000.0,0.0]}},{"arc":{"ccw":true,"center":[30000.0,5000.0],"from":[30000.0,0.0],"to":[35000.0,5000.0]}},{"line":{"from":[35000.0,5000.0],"to":[35000.0,60000.0]}},{"arc":{"ccw":true,"center":[25000.0,60000.0],"from":[35000.0,60000.0],"to":[25000.0,70000.0]}},{"arc":{"ccw":false,"center":[25000.0,80000.0],"from":[25000.0,70000.0],"to":[15000.0,80000.0]}},{"line":{"from":[15000.0,80000.0],"to":[15000.0,88000.0]}},{"arc":{"ccw":true,"center":[12000.0,88000.0],"from":[15000.0,88000.0],"to":[12000.0,91000.0]}},{"line":{"from":[12000.0,91000.0],"to":[0.0,91000.0]}}]}"#;
    let description = ObjectDescription::from_json(JAR_X1000).expect("well-formed");
    let (send, receive) = std::sync::mpsc::channel();
    // The build runs on its own thread so that a hang fails this test instead of the suite.
    std::thread::spawn(move || {
        let result = description.build(&OPTIONS).map(|m| {
            check_model(&m, "jar x1000");
            m.meshes.iter().map(|m| m.positions.len()).sum::<usize>()
        });
        let _ = send.send(result);
    });
    match receive.recv_timeout(Duration::from_secs(10)) {
        Ok(result) => println!("jar x1000: {result:?}"),
        Err(_) => panic!("jar x1000 at 0.5 mm: build still running after 10 s"),
    }
}

// ---------------------------------------------------------------------------------------------
// General (builder) objects: their numbers replaced by extreme values, keys dropped.

/// Every number in `value`, depth first.
fn numbers_mut(value: &mut Value) -> Vec<&mut Value> {
    match value {
        Value::Number(_) => vec![value],
        Value::Array(items) => items.iter_mut().flat_map(numbers_mut).collect(),
        Value::Object(map) => map.values_mut().flat_map(numbers_mut).collect(),
        _ => Vec::new(),
    }
}

#[test]
fn mutated_general_fixtures_never_panic() {
    const VALUES: [f64; 9] = [0.0, -1.0, 1e-300, 1e300, -1e300, 5e-324, 1e-9, 1e6, 0.5];
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/objects");
    let mut rng = SplitMix64(0x6E4E_2A11);
    let (mut cases, mut built, mut refused) = (0, 0, 0);
    let mut general = 0;
    for entry in std::fs::read_dir(&dir).expect("fixtures/objects") {
        let path = entry.expect("entry").path();
        if path.extension().is_none_or(|e| e != "json") || is_revolved(&path) {
            continue;
        }
        let text = std::fs::read_to_string(&path).expect("fixture");
        general += 1;
        let original: Value = serde_json::from_str(&text).expect("fixture JSON");
        for _ in 0..40 {
            let mut value = original.clone();
            let mut slots = numbers_mut(&mut value);
            for _ in 0..1 + rng.below(2) {
                let k = rng.below(slots.len());
                let v = VALUES[rng.below(VALUES.len())];
                *slots[k] = serde_json::json!(v);
            }
            let text = serde_json::to_string(&value).expect("serialise");
            cases += 1;
            let start = Instant::now();
            let result = ObjectFile::from_json(&text).map(|f| f.build(&OPTIONS));
            if std::env::var_os("ROBUST_TRACE").is_some() {
                eprintln!("TIME {:?} {text}", start.elapsed());
            }
            match result {
                Ok(Ok(model)) => {
                    built += 1;
                    check_model(&model, &text);
                }
                _ => refused += 1,
            }
        }
    }
    println!("general fixtures: {cases} cases, {built} built, {refused} refused");
    assert!(general >= 3, "the general fixture objects");
    assert!(refused > 0 && built > 0, "both outcomes are exercised");
}

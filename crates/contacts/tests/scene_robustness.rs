//! Bad input through the scene loader: random bytes, random JSON and mutated copies of the
//! fixture scenes (odd quaternions, huge translations, missing fields, wrong types, unknown
//! objects, inline bad profiles, bad options). Every case must end in `Ok` or a typed
//! `SceneError` (a panic fails the test); every scene that loads has finite, unit-rotation poses
//! and options that validate. Deterministic: a seeded SplitMix64.

use contacts::scene::Scene;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

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

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/scenes")
}

fn fixture_scenes() -> Vec<(String, Value)> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(scenes_dir()).expect("fixtures/scenes") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "json") {
            let text = std::fs::read_to_string(&path).expect("scene");
            let name = path
                .file_stem()
                .expect("stem")
                .to_string_lossy()
                .into_owned();
            out.push((name, serde_json::from_str(&text).expect("scene JSON")));
        }
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    assert!(out.len() >= 10, "the fixture scenes");
    out
}

#[derive(Default, Debug)]
struct Tally {
    cases: usize,
    ok: usize,
    err: usize,
}

/// Loads `text` as a scene; a panic fails the test. A loaded scene must be usable.
fn load(text: &str, tally: &mut Tally, what: &str) {
    tally.cases += 1;
    match Scene::from_json(text, Path::new("case.json"), &scenes_dir()) {
        Ok(scene) => {
            tally.ok += 1;
            assert!(scene.objects.len() >= 2, "{what}");
            for o in &scene.objects {
                let q = o.pose.rotation;
                assert!(
                    q.is_finite() && o.pose.translation.is_finite(),
                    "{what}: pose {:?}",
                    o.pose
                );
                assert!(
                    (q.length() - 1.0).abs() < 1e-12,
                    "{what}: |q| = {}",
                    q.length()
                );
            }
            assert!(scene.options.validate().is_ok(), "{what}");
        }
        Err(e) => {
            tally.err += 1;
            assert!(!e.to_string().is_empty(), "{what}: empty message");
        }
    }
}

fn num(v: f64) -> Value {
    serde_json::Number::from_f64(v).map_or(Value::Null, Value::Number)
}

/// Odd values for any field.
fn odd_value(rng: &mut SplitMix64) -> Value {
    rng.pick(&[
        Value::Null,
        json!(true),
        json!("pencil"),
        json!(""),
        json!([]),
        json!({}),
        json!([1, 2]),
        json!([0, 0, 0, 0]),
        json!([0, 0, 0, 2]),
        json!([1e300, 1e300, 1e300, 1e300]),
        json!([5e-324, 0, 0, 0]),
        json!([0.5, 0.5, 0.5, 0.5000001]),
        json!([0, 0, 0, 1, 0]),
        json!([-0.0, -0.0, -0.0, -1.0]),
        json!([1e6, 0, 0]),
        json!([1e12, -1e12, 1e300]),
        json!(-1),
        json!(0),
        json!(1e300),
        json!(5e-324),
        json!(-5e-324),
        json!(u64::MAX),
        json!(i64::MIN),
    ])
    .clone()
}

const OBJECT_REFERENCES: &[&str] = &[
    "pencil",
    "bowl",
    "teapot",
    "",
    ".",
    "..",
    "/",
    "missing.json",
    "../objects/pencil.json",
    "../objects/pencil.obj",
    "../objects",
    "nested/dir/",
    "pencil-bowl-one-contact.json",
    "\u{0}",
    "é.json",
];

/// An inline object with a (usually bad) profile.
fn inline_object(rng: &mut SplitMix64) -> Value {
    let profile = match rng.below(7) {
        0 => json!([]),
        1 => json!([{"line": {"from": [0, 0], "to": [10, 0]}}]),
        2 => json!([
            {"line": {"from": [0, 0], "to": [10, 0]}},
            {"line": {"from": [10, 0], "to": [0, 10]}},
            {"line": {"from": [0, 10], "to": [10, 10]}}
        ]),
        3 => json!([{"arc": {"center": [0, 0], "from": [0, -0.0], "to": [0, 0], "ccw": true}}]),
        4 => json!([{"arc": {"center": [0, 0], "from": [0, -5], "to": [0, 5], "ccw": true}}]),
        5 => json!([{"bezier": {"points": [[0, 0], [1e300, 0], [1e300, 1], [0, 1]]}}]),
        _ => json!([{"circle": {"r": 1}}]),
    };
    let mut object = json!({"name": "inline", "profile": profile});
    if rng.below(5) == 0 {
        object["extra"] = json!(1);
    }
    object
}

/// `v[key]`, first turning `v` into an object if it is not one (indexing would panic).
fn field<'a>(v: &'a mut Value, key: &str) -> &'a mut Value {
    if !v.is_object() {
        *v = json!({});
    }
    &mut v[key]
}

/// One random mutation of a scene value; returns its name.
fn mutate(rng: &mut SplitMix64, scene: &mut Value) -> &'static str {
    let n_objects = scene["objects"].as_array().map_or(0, Vec::len);
    let i = if n_objects == 0 {
        0
    } else {
        rng.below(n_objects)
    };
    let choice = rng.below(13);
    if choice <= 6 && n_objects == 0 {
        return "no object to mutate";
    }
    match choice {
        0 => {
            let q = [
                rng.pick(&[0.0, 1.0, -1.0, 0.5, 1e-300, 1e300, 5e-324, -0.0]),
                rng.pick(&[0.0, 1.0, std::f64::consts::FRAC_1_SQRT_2, 1e300]),
                rng.pick(&[0.0, 2.0, -0.0]),
                rng.pick(&[0.0, 1.0, 1.000001, 1.0000001, 0.9999999]),
            ];
            *field(field(&mut scene["objects"][i], "pose"), "rotation") =
                json!([*q[0], *q[1], *q[2], *q[3]]);
            "odd quaternion"
        }
        1 => {
            let t = *rng.pick(&[1e6, 1e12, 1e300, -1e300, f64::MAX, 5e-324]);
            *field(field(&mut scene["objects"][i], "pose"), "translation") =
                json!([t, -t, t * rng.unit()]);
            "huge translation"
        }
        2 => {
            let key = *rng.pick(&["name", "object", "pose"]);
            if let Some(o) = scene["objects"][i].as_object_mut() {
                o.remove(key);
            }
            "missing object field"
        }
        3 => {
            let key = *rng.pick(&["name", "object", "pose", "bogus"]);
            *field(&mut scene["objects"][i], key) = odd_value(rng);
            "wrong type in object"
        }
        4 => {
            let key = *rng.pick(&["translation", "rotation", "scale"]);
            *field(field(&mut scene["objects"][i], "pose"), key) = odd_value(rng);
            "wrong type in pose"
        }
        5 => {
            *field(&mut scene["objects"][i], "object") = json!(*rng.pick(OBJECT_REFERENCES));
            "odd object reference"
        }
        6 => {
            *field(&mut scene["objects"][i], "object") = inline_object(rng);
            "inline bad profile"
        }
        7 => {
            let key = *rng.pick(&["margin", "delta1", "delta2", "chordal_tolerance", "depth"]);
            let v = rng
                .pick(&[
                    num(0.0),
                    num(-1.0),
                    num(-0.0),
                    num(1e300),
                    num(-1e300),
                    num(5e-324),
                    num(1e-12),
                    num(f64::MAX),
                    json!("0.1"),
                    Value::Null,
                ])
                .clone();
            if !scene["options"].is_object() {
                scene["options"] = json!({});
            }
            scene["options"][key] = v;
            "bad option"
        }
        8 => {
            scene["options"] = odd_value(rng);
            "options of the wrong type"
        }
        9 => {
            if let Some(list) = scene["objects"].as_array_mut() {
                if !list.is_empty() {
                    list.remove(i);
                }
            }
            "drop object"
        }
        10 => {
            if let Some(list) = scene["objects"].as_array_mut() {
                let extra = list.get(i).cloned().unwrap_or(Value::Null);
                list.push(extra);
            }
            "duplicate object"
        }
        11 => {
            let key = *rng.pick(&["objects", "options", "note", "extra"]);
            if rng.below(2) == 0 {
                if let Some(o) = scene.as_object_mut() {
                    o.remove(key);
                }
            } else {
                scene[key] = odd_value(rng);
            }
            "root field"
        }
        _ => {
            *scene = odd_value(rng);
            "whole scene replaced"
        }
    }
}

#[test]
fn mutated_scenes_never_panic() {
    let mut rng = SplitMix64(0x5CE_4E5);
    let mut tally = Tally::default();
    let mut by_mutation: std::collections::BTreeMap<&str, usize> = Default::default();
    for (name, original) in fixture_scenes() {
        // The fixture itself loads.
        let text = serde_json::to_string(&original).expect("serialise");
        load(&text, &mut tally, &name);
        for _ in 0..150 {
            let mut value = original.clone();
            let mut applied = Vec::new();
            for _ in 0..1 + rng.below(3) {
                if !value.is_object() {
                    break;
                }
                let m = mutate(&mut rng, &mut value);
                *by_mutation.entry(m).or_default() += 1;
                applied.push(m);
            }
            let text = serde_json::to_string(&value).expect("serialise");
            load(
                &text,
                &mut tally,
                &format!("{name} after {applied:?}: {text}"),
            );
        }
    }
    println!("{tally:?}\n{by_mutation:?}");
    assert!(tally.ok > 0 && tally.err > 0, "{tally:?}");
}

#[test]
fn random_bytes_and_text_never_panic() {
    let mut rng = SplitMix64(0xB17E5);
    let mut tally = Tally::default();
    const ALPHABET: &[u8] = b"{}[]\",:0123456789.eE+-objectsposerotaintl \n";
    for case in 0..3000 {
        let len = rng.below(128);
        let bytes: Vec<u8> = if case % 2 == 0 {
            (0..len).map(|_| rng.next_u64() as u8).collect()
        } else {
            (0..len).map(|_| *rng.pick(ALPHABET)).collect()
        };
        load(&String::from_utf8_lossy(&bytes), &mut tally, "random bytes");
    }
    // Number literals at the edges of f64 in every numeric slot of a minimal scene.
    const NUMBERS: &[&str] = &[
        "0",
        "-0.0",
        "1e300",
        "-1e300",
        "5e-324",
        "1e400",
        "1e-400",
        "1e99999999999999999999",
        "123456789012345678901234567890",
        "1.0000001",
        "0.9999999",
    ];
    for _ in 0..1000 {
        let mut n = || *rng.pick(NUMBERS);
        let text = format!(
            r#"{{"objects": [
                {{"name": "a", "object": "pencil", "pose": {{"translation": [{}, {}, {}], "rotation": [{}, {}, {}, {}]}}}},
                {{"name": "b", "object": "bowl"}}],
              "options": {{"margin": {}, "delta1": {}, "delta2": {}, "chordal_tolerance": {}}}}}"#,
            n(),
            n(),
            n(),
            n(),
            n(),
            n(),
            n(),
            n(),
            n(),
            n(),
            n()
        );
        load(&text, &mut tally, &text);
    }
    // Deep nesting.
    for depth in [127, 128, 129, 10_000] {
        load(&"[".repeat(depth), &mut tally, "deep arrays");
        load(
            &format!(r#"{{"objects": {}"#, "[".repeat(depth)),
            &mut tally,
            "deep objects",
        );
    }
    println!("{tally:?}");
    assert_eq!(tally.cases, 4008);
}

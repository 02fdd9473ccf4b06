//! The scene file: objects with poses, and query options.
//!
//! ```json
//! { "objects": [
//!     {"name": "pencil", "object": "pencil",
//!      "pose": {"translation": [0, 0, 0], "rotation": [0, 0, 0, 1]}},
//!     {"name": "cup", "object": "my/cup.json",
//!      "pose": {"translation": [10, 0, 0], "rotation": [0, 0, 0.7071067811865476, 0.7071067811865476]}} ],
//!   "options": {"margin": 1.0, "delta1": -0.001, "delta2": 0.1, "chordal_tolerance": 0.05} }
//! ```
//! Lengths in mm; rotation a unit quaternion [x, y, z, w]. `object` is a built-in object name,
//! a path to an object file relative to the scene file, or an inline object (a solid of
//! revolution with a `profile`, or a general solid such as `{"name": "box", "rounded_box":
//! {"half_extents": [20, 15, 10], "radius": 3}}`, see `geom_param::SolidDescription`).
//! `object` may also name a STEP file (`.step` / `.stp`, relative to the scene file), with an
//! optional `"solid"` beside it: the index (in `#id` order) or name of one of the file's
//! solids, the first when left out. `options` and each of its fields may be left out.

use crate::builtin_objects::builtin_object;
use contact_pipeline::{ContactOptions, OptionsError};
use geom_param::{
    DPose3, DQuat, DVec3, ObjectFile, ObjectFileError, SolidDescription, SolidSpec, StepSolidRef,
};
use serde_json::{Map, Value};
use std::path::{Path, PathBuf};

/// Largest object file read (bytes).
const MAX_OBJECT_FILE_BYTES: u64 = 16 << 20;

/// How far a rotation quaternion's norm may be from 1 (it is then normalised).
const UNIT_TOLERANCE: f64 = 1e-6;

/// One object of a scene.
#[derive(Clone, Debug)]
pub struct SceneObject {
    /// Its name in the scene.
    pub name: String,
    /// Its description (a profile, or a general solid's builder).
    pub description: ObjectFile,
    /// Its pose in the world frame.
    pub pose: DPose3,
}

/// A scene: objects and options.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The objects; every pair is queried.
    pub objects: Vec<SceneObject>,
    /// Query options.
    pub options: ContactOptions,
}

/// Why a scene could not be read.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("cannot read {path}: {message}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The system's message.
        message: String,
    },
    /// The text is not JSON.
    #[error("{path}: malformed JSON at line {line}, column {column}: {message}")]
    Syntax {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The parser's message.
        message: String,
    },
    /// A field the format does not know.
    #[error("{at}: unknown field `{field}`")]
    UnknownField {
        /// Where.
        at: String,
        /// The field.
        field: String,
    },
    /// A required field is missing.
    #[error("{at}: missing field `{field}`")]
    MissingField {
        /// Where.
        at: String,
        /// The field.
        field: &'static str,
    },
    /// A value of the wrong type or shape.
    #[error("{at}: expected {expected}")]
    WrongType {
        /// Where.
        at: String,
        /// What was expected.
        expected: &'static str,
    },
    /// `object` names no built-in object and no readable file.
    #[error(
        "{at}: unknown object `{name}` (built-in objects: paperweight, goblet, bowl, pencil, jar, vase, rounded-box, tube, bracket, loft; or a path to an object file)"
    )]
    UnknownObject {
        /// Where.
        at: String,
        /// The name given.
        name: String,
    },
    /// A pose that is not a rigid motion.
    #[error("{at}: bad pose: {reason}")]
    BadPose {
        /// Where.
        at: String,
        /// What is wrong.
        reason: String,
    },
    /// An object file or inline object that does not load.
    #[error("{at}: {source}")]
    Object {
        /// Where.
        at: String,
        /// Why.
        source: ObjectFileError,
    },
    /// Options that cannot work together.
    #[error("options: {0}")]
    Options(#[from] OptionsError),
    /// Fewer than two objects.
    #[error("a scene needs at least two objects, found {0}")]
    TooFewObjects(usize),
}

impl Scene {
    /// Reads a scene file; relative object paths are resolved against its folder.
    ///
    /// # Errors
    /// A [`SceneError`] saying what is wrong and where.
    pub fn from_file(path: &Path) -> Result<Self, SceneError> {
        let text = read_limited(path)?;
        let base = path.parent().unwrap_or(Path::new("."));
        Self::from_json(&text, path, base)
    }

    /// Parses scene text; `path` names it in errors and `base` resolves relative object paths.
    ///
    /// # Errors
    /// A [`SceneError`] saying what is wrong and where.
    pub fn from_json(text: &str, path: &Path, base: &Path) -> Result<Self, SceneError> {
        let value: Value = serde_json::from_str(text).map_err(|e| SceneError::Syntax {
            path: path.to_path_buf(),
            line: e.line(),
            column: e.column(),
            message: e.to_string(),
        })?;
        let root = object(&value, "scene", &["objects", "options", "note"])?;
        let Some(Value::Array(items)) = root.get("objects") else {
            return Err(match root.get("objects") {
                None => SceneError::MissingField {
                    at: "scene".into(),
                    field: "objects",
                },
                Some(_) => wrong("scene.objects", "an array of objects"),
            });
        };
        let objects = items
            .iter()
            .enumerate()
            .map(|(i, item)| scene_object(item, &format!("objects[{i}]"), base))
            .collect::<Result<Vec<_>, _>>()?;
        if objects.len() < 2 {
            return Err(SceneError::TooFewObjects(objects.len()));
        }
        let options = match root.get("options") {
            None => ContactOptions::default(),
            Some(v) => options(v)?,
        };
        options.validate()?;
        Ok(Self { objects, options })
    }
}

fn wrong(at: &str, expected: &'static str) -> SceneError {
    SceneError::WrongType {
        at: at.into(),
        expected,
    }
}

fn object<'a>(
    value: &'a Value,
    at: &str,
    allowed: &[&str],
) -> Result<&'a Map<String, Value>, SceneError> {
    let Value::Object(map) = value else {
        return Err(wrong(at, "an object"));
    };
    if let Some(field) = map.keys().find(|k| !allowed.contains(&k.as_str())) {
        return Err(SceneError::UnknownField {
            at: at.into(),
            field: field.clone(),
        });
    }
    Ok(map)
}

fn numbers<const N: usize>(
    value: &Value,
    at: &str,
    expected: &'static str,
) -> Result<[f64; N], SceneError> {
    let list = value
        .as_array()
        .filter(|l| l.len() == N)
        .ok_or_else(|| wrong(at, expected))?;
    let mut out = [0.0; N];
    for (o, v) in out.iter_mut().zip(list) {
        *o = v.as_f64().ok_or_else(|| wrong(at, expected))?;
    }
    Ok(out)
}

fn scene_object(value: &Value, at: &str, base: &Path) -> Result<SceneObject, SceneError> {
    let map = object(value, at, &["name", "object", "solid", "pose"])?;
    let name = match map.get("name") {
        Some(Value::String(s)) => s.clone(),
        Some(_) => return Err(wrong(&format!("{at}.name"), "a string")),
        None => {
            return Err(SceneError::MissingField {
                at: at.into(),
                field: "name",
            });
        }
    };
    let object_at = format!("{at}.object");
    let description = match map.get("object") {
        None => {
            return Err(SceneError::MissingField {
                at: at.into(),
                field: "object",
            });
        }
        Some(Value::String(reference)) if is_step(reference) => {
            step_object(reference, map.get("solid"), at, base)?
        }
        Some(Value::String(reference)) => load_reference(reference, &object_at, base)?,
        Some(inline @ Value::Object(_)) => ObjectFile::from_json_value(inline, &object_at)
            .map_err(|source| SceneError::Object {
                at: object_at.clone(),
                source,
            })?,
        Some(_) => {
            return Err(wrong(
                &object_at,
                "an object name, a path, or an inline object",
            ));
        }
    };
    if map.contains_key("solid")
        && !matches!(&description, ObjectFile::General(d) if matches!(d.spec, SolidSpec::Step { .. }))
    {
        return Err(wrong(
            &format!("{at}.solid"),
            "no `solid` field unless `object` names a STEP file",
        ));
    }
    let pose = match map.get("pose") {
        None => DPose3::IDENTITY,
        Some(v) => pose(v, &format!("{at}.pose"))?,
    };
    Ok(SceneObject {
        name,
        description,
        pose,
    })
}

/// True for a path with a STEP extension (`.step`, `.stp`, any case).
fn is_step(reference: &str) -> bool {
    Path::new(reference)
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("step") || e.eq_ignore_ascii_case("stp"))
}

/// A STEP file object: the file resolved against the scene's folder, the solid chosen by
/// `solid` (an index or a name). The file is read when the object is built.
fn step_object(
    reference: &str,
    solid: Option<&Value>,
    at: &str,
    base: &Path,
) -> Result<ObjectFile, SceneError> {
    let solid = match solid {
        None => None,
        Some(Value::Number(n)) => Some(StepSolidRef::Index(
            n.as_u64()
                .and_then(|i| usize::try_from(i).ok())
                .ok_or_else(|| {
                    wrong(
                        &format!("{at}.solid"),
                        "a solid index (an integer >= 0) or name",
                    )
                })?,
        )),
        Some(Value::String(name)) => Some(StepSolidRef::Name(name.clone())),
        Some(_) => {
            return Err(wrong(
                &format!("{at}.solid"),
                "a solid index (an integer >= 0) or name",
            ));
        }
    };
    let path = base.join(reference);
    let name = Path::new(reference)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("step")
        .to_string();
    Ok(ObjectFile::General(SolidDescription {
        name,
        note: None,
        spec: SolidSpec::Step {
            file: path.to_string_lossy().into_owned(),
            solid,
        },
    }))
}

fn load_reference(reference: &str, at: &str, base: &Path) -> Result<ObjectFile, SceneError> {
    let parse = |text: &str| {
        ObjectFile::from_json(text).map_err(|source| SceneError::Object {
            at: at.into(),
            source,
        })
    };
    if let Some(text) = builtin_object(reference) {
        return parse(text);
    }
    let path = base.join(reference);
    match read_limited(&path) {
        Ok(text) => parse(&text),
        Err(_) if !reference.ends_with(".json") && !reference.contains('/') => {
            Err(SceneError::UnknownObject {
                at: at.into(),
                name: reference.into(),
            })
        }
        Err(e) => Err(e),
    }
}

/// Reads a scene or object file, refusing anything but a regular file of at most
/// `MAX_OBJECT_FILE_BYTES` (a device such as /dev/zero would never end).
fn read_limited(path: &Path) -> Result<String, SceneError> {
    let io = |message: String| SceneError::Io {
        path: path.to_path_buf(),
        message,
    };
    let meta = std::fs::metadata(path).map_err(|e| io(e.to_string()))?;
    if !meta.is_file() || meta.len() > MAX_OBJECT_FILE_BYTES {
        return Err(io(format!(
            "not a regular file of at most {MAX_OBJECT_FILE_BYTES} bytes"
        )));
    }
    std::fs::read_to_string(path).map_err(|e| io(e.to_string()))
}

fn pose(value: &Value, at: &str) -> Result<DPose3, SceneError> {
    let map = object(value, at, &["translation", "rotation"])?;
    let translation = match map.get("translation") {
        None => [0.0; 3],
        Some(v) => numbers::<3>(
            v,
            &format!("{at}.translation"),
            "[x, y, z] of three numbers",
        )?,
    };
    let rotation = match map.get("rotation") {
        None => [0.0, 0.0, 0.0, 1.0],
        Some(v) => numbers::<4>(
            v,
            &format!("{at}.rotation"),
            "a quaternion [x, y, z, w] of four numbers",
        )?,
    };
    let bad = |reason: String| SceneError::BadPose {
        at: at.into(),
        reason,
    };
    if translation.iter().chain(&rotation).any(|c| !c.is_finite()) {
        return Err(bad("a component is not a finite number".into()));
    }
    let q = DQuat::from_array(rotation);
    let norm = q.length();
    if (norm - 1.0).abs() > UNIT_TOLERANCE {
        return Err(bad(format!("rotation quaternion has norm {norm}, not 1")));
    }
    Ok(DPose3 {
        rotation: q / norm,
        translation: DVec3::from_array(translation),
    })
}

fn options(value: &Value) -> Result<ContactOptions, SceneError> {
    let map = object(
        value,
        "options",
        &["margin", "delta1", "delta2", "chordal_tolerance"],
    )?;
    let mut options = ContactOptions::default();
    for (name, slot) in [
        ("margin", &mut options.margin),
        ("delta1", &mut options.delta1),
        ("delta2", &mut options.delta2),
        ("chordal_tolerance", &mut options.chordal_tolerance),
    ] {
        if let Some(v) = map.get(name) {
            *slot = v
                .as_f64()
                .ok_or_else(|| wrong(&format!("options.{name}"), "a number (mm)"))?;
        }
    }
    Ok(options)
}

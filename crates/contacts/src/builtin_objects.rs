//! The fixture objects (the six paper objects and the general solids), built into the command
//! so that scenes can name them.

/// (name, object file text) of every built-in object.
pub const BUILTIN_OBJECTS: [(&str, &str); 9] = [
    (
        "paperweight",
        include_str!("../../../fixtures/objects/paperweight.json"),
    ),
    (
        "goblet",
        include_str!("../../../fixtures/objects/goblet.json"),
    ),
    ("bowl", include_str!("../../../fixtures/objects/bowl.json")),
    (
        "pencil",
        include_str!("../../../fixtures/objects/pencil.json"),
    ),
    ("jar", include_str!("../../../fixtures/objects/jar.json")),
    ("vase", include_str!("../../../fixtures/objects/vase.json")),
    (
        "rounded-box",
        include_str!("../../../fixtures/objects/rounded-box.json"),
    ),
    ("tube", include_str!("../../../fixtures/objects/tube.json")),
    (
        "bracket",
        include_str!("../../../fixtures/objects/bracket.json"),
    ),
];

/// The object file text of a built-in object.
#[must_use]
pub fn builtin_object(name: &str) -> Option<&'static str> {
    BUILTIN_OBJECTS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, text)| *text)
}

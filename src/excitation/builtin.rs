//! Built-in excitations: the TOML files of `excitations/`, embedded in the binary, and the input
//! spectral classes of the seat tests ([`super::classes`]).

/// (name, TOML text) of every built-in excitation.
pub const BUILTINS: &[(&str, &str)] = &[
    (
        "white-0.5-80",
        include_str!("../../excitations/white-0.5-80.toml"),
    ),
    ("bell-214", include_str!("../../excitations/bell-214.toml")),
    (
        "road-c-72kmh",
        include_str!("../../excitations/road-c-72kmh.toml"),
    ),
    ("sine-4hz", include_str!("../../excitations/sine-4hz.toml")),
    (
        "sweep-0.5-20",
        include_str!("../../excitations/sweep-0.5-20.toml"),
    ),
];

/// Names of the built-ins: the files, then the input spectral classes of [`super::classes`].
pub fn names() -> Vec<&'static str> {
    BUILTINS
        .iter()
        .map(|(n, _)| *n)
        .chain(super::classes::CLASSES.iter().map(|c| c.name))
        .collect()
}

/// The TOML text of built-in `name`.
pub fn text(name: &str) -> Option<&'static str> {
    BUILTINS.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

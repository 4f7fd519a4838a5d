//! The examples, embedded: the page's New menu lists them, and opens each
//! as a new document (Save downloads it; the file served is not touched).

/// Every example file, by name, with its text. A file added to
/// `examples/` must be added here (the test below says so).
pub(crate) static EXAMPLES: &[(&str, &str)] = &[
    ("2dtree.od", include_str!("../../examples/2dtree.od")),
    (
        "abop-1.24a.lsys",
        include_str!("../../examples/abop-1.24a.lsys"),
    ),
    (
        "abop-1.24b.lsys",
        include_str!("../../examples/abop-1.24b.lsys"),
    ),
    (
        "abop-1.24c.lsys",
        include_str!("../../examples/abop-1.24c.lsys"),
    ),
    (
        "abop-1.24d.lsys",
        include_str!("../../examples/abop-1.24d.lsys"),
    ),
    (
        "abop-1.24e.lsys",
        include_str!("../../examples/abop-1.24e.lsys"),
    ),
    (
        "abop-1.24f.lsys",
        include_str!("../../examples/abop-1.24f.lsys"),
    ),
    (
        "abop-1.26.lsys",
        include_str!("../../examples/abop-1.26.lsys"),
    ),
    (
        "abop-1.27.lsys",
        include_str!("../../examples/abop-1.27.lsys"),
    ),
    (
        "abop-1.31a.lsys",
        include_str!("../../examples/abop-1.31a.lsys"),
    ),
    (
        "abop-1.31b.lsys",
        include_str!("../../examples/abop-1.31b.lsys"),
    ),
    (
        "abop-1.31c.lsys",
        include_str!("../../examples/abop-1.31c.lsys"),
    ),
    (
        "abop-1.31d.lsys",
        include_str!("../../examples/abop-1.31d.lsys"),
    ),
    (
        "abop-1.31e.lsys",
        include_str!("../../examples/abop-1.31e.lsys"),
    ),
    (
        "abop-1.35.lsys",
        include_str!("../../examples/abop-1.35.lsys"),
    ),
    (
        "abop-2.6a.lsys",
        include_str!("../../examples/abop-2.6a.lsys"),
    ),
    (
        "abop-2.6b.lsys",
        include_str!("../../examples/abop-2.6b.lsys"),
    ),
    (
        "abop-2.6c.lsys",
        include_str!("../../examples/abop-2.6c.lsys"),
    ),
    (
        "abop-2.6d.lsys",
        include_str!("../../examples/abop-2.6d.lsys"),
    ),
    (
        "abop-2.7a.lsys",
        include_str!("../../examples/abop-2.7a.lsys"),
    ),
    (
        "abop-2.7b.lsys",
        include_str!("../../examples/abop-2.7b.lsys"),
    ),
    (
        "abop-2.7c.lsys",
        include_str!("../../examples/abop-2.7c.lsys"),
    ),
    (
        "abop-2.7d.lsys",
        include_str!("../../examples/abop-2.7d.lsys"),
    ),
    (
        "abop-2.8a.lsys",
        include_str!("../../examples/abop-2.8a.lsys"),
    ),
    (
        "abop-2.8b.lsys",
        include_str!("../../examples/abop-2.8b.lsys"),
    ),
    (
        "abop-2.8c.lsys",
        include_str!("../../examples/abop-2.8c.lsys"),
    ),
    (
        "abop-2.8d.lsys",
        include_str!("../../examples/abop-2.8d.lsys"),
    ),
    (
        "abop-3.2.lsys",
        include_str!("../../examples/abop-3.2.lsys"),
    ),
    (
        "abop-5.5a.lsys",
        include_str!("../../examples/abop-5.5a.lsys"),
    ),
    (
        "alternatives.od",
        include_str!("../../examples/alternatives.od"),
    ),
    ("crown.od", include_str!("../../examples/crown.od")),
    ("decrement.od", include_str!("../../examples/decrement.od")),
    ("fig9.od", include_str!("../../examples/fig9.od")),
    ("forest3d.od", include_str!("../../examples/forest3d.od")),
    ("grove.od", include_str!("../../examples/grove.od")),
    ("hilbert.lsys", include_str!("../../examples/hilbert.lsys")),
    (
        "hilbert3d.lsys",
        include_str!("../../examples/hilbert3d.lsys"),
    ),
    ("holes.od", include_str!("../../examples/holes.od")),
    (
        "koch-snowflake.lsys",
        include_str!("../../examples/koch-snowflake.lsys"),
    ),
    (
        "oak3d-bare.od",
        include_str!("../../examples/oak3d-bare.od"),
    ),
    ("oak3d.od", include_str!("../../examples/oak3d.od")),
    (
        "paper-worked.bed",
        include_str!("../../examples/paper-worked.bed"),
    ),
    (
        "param-willow.lsys",
        include_str!("../../examples/param-willow.lsys"),
    ),
    ("pentagon.od", include_str!("../../examples/pentagon.od")),
    (
        "plant3d-bare.lsys",
        include_str!("../../examples/plant3d-bare.lsys"),
    ),
    ("plant3d.lsys", include_str!("../../examples/plant3d.lsys")),
    ("polygon.od", include_str!("../../examples/polygon.od")),
    (
        "seed-r1r2r2.bed",
        include_str!("../../examples/seed-r1r2r2.bed"),
    ),
    (
        "sierpinski-arrowhead.lsys",
        include_str!("../../examples/sierpinski-arrowhead.lsys"),
    ),
    (
        "stl-003-fig4.lsys",
        include_str!("../../examples/stl-003-fig4.lsys"),
    ),
    (
        "successors.od",
        include_str!("../../examples/successors.od"),
    ),
];

#[cfg(test)]
mod tests {
    use super::*;

    /// The table holds every `.od`, `.bed` and `.lsys` in examples/, with
    /// its text, in name order.
    #[test]
    fn every_example_is_embedded() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
        let mut on_disk: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .filter_map(|e| {
                let name = e.unwrap().file_name().into_string().unwrap();
                [".od", ".bed", ".lsys"]
                    .iter()
                    .any(|x| name.ends_with(x))
                    .then_some(name)
            })
            .collect();
        on_disk.sort();
        let names: Vec<&str> = EXAMPLES.iter().map(|(n, _)| *n).collect();
        assert_eq!(names, on_disk);
        for (name, text) in EXAMPLES {
            assert_eq!(
                *text,
                std::fs::read_to_string(dir.join(name)).unwrap(),
                "{name}"
            );
        }
    }
}

//! The SolveSpace reader on mutated files: truncations, byte edits, shuffled lines and odd
//! values put into known keys. It returns a sketch list or an error; it never panics.

mod common;

use std::path::Path;
use std::sync::OnceLock;

use proptest::prelude::*;

/// The files mutated: the corpus (when present) and the hand-written files.
fn files() -> &'static [Vec<u8>] {
    static FILES: OnceLock<Vec<Vec<u8>>> = OnceLock::new();
    FILES.get_or_init(|| {
        let mut paths = common::files_with_suffix(
            &Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/slvs"),
            ".slvs",
        );
        if let Some(dir) = common::external() {
            paths.extend(common::files_with_suffix(&dir.join("solvespace"), ".slvs"));
        }
        paths.iter().map(|p| std::fs::read(p).expect("readable")).collect()
    })
}

fn pick(i: usize) -> &'static [u8] {
    let files = files();
    &files[i % files.len()]
}

fn at(len: usize, fraction: f64) -> usize {
    ((len as f64 * fraction) as usize).min(len)
}

/// Reads, and checks what every answer must satisfy.
fn check(bytes: &[u8]) {
    match gcs_import::slvs::read("fuzz.slvs", bytes) {
        Ok(sketches) => {
            for s in &sketches {
                assert!(s.dim == 2 || s.dim == 3);
                for c in &s.constraints {
                    for r in &c.refs {
                        assert!(s.entities.iter().any(|e| e.id == r.entity), "{}", r.entity);
                    }
                }
            }
        }
        Err(e) => {
            assert_eq!(e.file, "fuzz.slvs");
            assert!(!e.message.is_empty());
        }
    }
}

/// Values that a key may get: edge cases of each format.
const ODD_VALUES: [&str; 16] = [
    "",
    "0",
    "-1",
    "nan",
    "-inf",
    "1e9999",
    "1e-400",
    "99999999999999999999999",
    "ffffffff",
    "80000000",
    "00010001",
    "00040001",
    "80020000",
    "2147483647",
    "12000",
    "{",
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn truncations(file in any::<usize>(), cut in 0.0f64..1.0) {
        let bytes = pick(file);
        check(&bytes[..at(bytes.len(), cut)]);
    }

    #[test]
    fn byte_edits(
        file in any::<usize>(),
        edits in prop::collection::vec((0.0f64..1.0, any::<u8>(), 0u8..3), 1..12),
    ) {
        let mut bytes = pick(file).to_vec();
        for (place, byte, how) in edits {
            let i = at(bytes.len(), place);
            match how {
                0 if i < bytes.len() => bytes[i] = byte,
                1 => bytes.insert(i, byte),
                _ if i < bytes.len() => { bytes.remove(i); }
                _ => {}
            }
        }
        check(&bytes);
    }

    #[test]
    fn line_edits(
        file in any::<usize>(),
        edits in prop::collection::vec((0.0f64..1.0, 0.0f64..1.0, 0u8..3), 1..6),
    ) {
        let bytes = pick(file);
        let mut lines: Vec<&[u8]> = bytes.split(|b| *b == b'\n').collect();
        for (a, b, how) in edits {
            let n = lines.len();
            let (i, j) = (at(n, a).min(n - 1), at(n, b).min(n - 1));
            match how {
                0 => lines.swap(i, j),
                1 => { let l = lines[j]; lines.insert(i, l); }
                _ => { lines.remove(i); if lines.is_empty() { lines.push(b""); } }
            }
        }
        check(&lines.join(&b'\n'));
    }

    #[test]
    fn odd_values(
        file in any::<usize>(),
        edits in prop::collection::vec((0.0f64..1.0, 0usize..ODD_VALUES.len()), 1..6),
    ) {
        let bytes = pick(file);
        let mut lines: Vec<Vec<u8>> = bytes.split(|b| *b == b'\n').map(<[u8]>::to_vec).collect();
        let keyed: Vec<usize> =
            (0..lines.len()).filter(|&i| lines[i].contains(&b'=')).collect();
        for (place, value) in edits {
            if keyed.is_empty() {
                break;
            }
            let i = keyed[at(keyed.len(), place).min(keyed.len() - 1)];
            let eq = lines[i].iter().position(|b| *b == b'=').unwrap_or(0);
            lines[i].truncate(eq + 1);
            lines[i].extend_from_slice(ODD_VALUES[value].as_bytes());
        }
        check(&lines.join(&b'\n'));
    }
}

/// Handles pointed at every entity of the file in turn: wrong types must be skipped, not
/// panic.
#[test]
fn handles_pointed_anywhere() {
    for bytes in files().iter() {
        let text = bytes.clone();
        let handles: Vec<Vec<u8>> = text
            .split(|b| *b == b'\n')
            .filter_map(|l| l.strip_prefix(b"Entity.h.v=".as_slice()))
            .map(<[u8]>::to_vec)
            .collect();
        for key in [&b"Constraint.ptA.v="[..], b"Constraint.entityA.v=", b"Constraint.entityB.v="] {
            for h in handles.iter() {
                let mut out = Vec::new();
                for line in text.split(|b| *b == b'\n') {
                    if line.starts_with(key) {
                        out.extend_from_slice(key);
                        out.extend_from_slice(h);
                    } else {
                        out.extend_from_slice(line);
                    }
                    out.push(b'\n');
                }
                check(&out);
            }
        }
    }
}

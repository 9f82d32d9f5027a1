//! `gcs navigate` end to end: the page embeds every realization of the closed-form steps (each
//! satisfying every constraint), the drawing's choices as autosolve, the plan; a CAD file opens,
//! and a sketch it does not hold is refused with the names it does. (The page itself is driven in a browser by
//! `tests/navigate_browser.sh`, which CI runs.)

mod common;

use common::gcs;
use serde_json::Value;

fn temp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("gcs-navigate-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// The data the page embeds.
fn embedded(page: &str) -> Value {
    let marker = r#"<script type="application/json" id="data">"#;
    let start = page.find(marker).expect("data") + marker.len();
    let end = start + page[start..].find("</script>").expect("end of data");
    serde_json::from_str(&page[start..end].replace("<\\/", "</")).expect("JSON")
}

#[test]
fn the_page_holds_every_realization_and_the_drawings_choices() {
    let page = temp("chain.html");
    let (code, _, err) = gcs(&["navigate", "data/paper/chain.ron", "-o", page.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let page = std::fs::read_to_string(&page).unwrap();
    assert!(page.contains("<title>gcs navigate: chain</title>"));
    let d = embedded(&page);
    // The same realizations as `gcs solve --all`.
    let (_, out, _) = gcs(&["solve", "--all", "--format", "json", "data/paper/chain.ron"]);
    let solved: Value = serde_json::from_str(out.trim()).unwrap();
    let realizations = d["realizations"].as_array().unwrap();
    assert_eq!(realizations.len(), solved["solutions"].as_array().unwrap().len());
    assert!(realizations.len() > 2, "{}", realizations.len());
    let mut seen = std::collections::BTreeSet::new();
    for r in realizations {
        assert!(r["max_residual"].as_f64().unwrap() <= 1e-9, "{}", r["max_residual"]);
        assert!(r["svg"].as_str().unwrap().starts_with("<svg"));
        assert!(r["ron"].as_str().unwrap().contains("System("));
        assert!(seen.insert(r["choices"].to_string()), "distinct choices");
    }
    // Autosolve: the choices of the plan `gcs solve` reports (the core's node, one distance,
    // then the closed-form steps).
    let chosen: Vec<Value> =
        solved["plan"].as_array().unwrap().iter().map(|p| p["chosen"].clone()).collect();
    let autosolve = d["autosolve"].as_u64().unwrap() as usize;
    assert_eq!(realizations[autosolve]["choices"], Value::from(chosen));
    assert_eq!(d["plan"].as_array().unwrap().len(), solved["plan"].as_array().unwrap().len());
}

/// Two K3,3 joined by three distances: the page offers the candidates of each node of the
/// core's DR-plan — each K3,3's real realizations and their assembly — and embeds every
/// combination, each satisfying every constraint.
#[test]
fn the_core_nodes_candidates_are_offered() {
    let page = temp("two_k33.html");
    let (code, _, err) = gcs(&["navigate", "data/paper/two_k33.ron", "-o", page.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let d = embedded(&std::fs::read_to_string(&page).unwrap());
    let plan = d["plan"].as_array().unwrap();
    assert_eq!(plan.len(), 3);
    assert_eq!(plan[2]["children"], serde_json::json!([0, 1]));
    for (k, p) in plan.iter().enumerate() {
        assert_eq!(p["choice"].as_u64(), Some(k as u64), "{p}");
        assert!(p["offered"].as_u64().unwrap() >= 2, "{p}");
        assert_eq!(p["paths"]["failed"], 0, "{p}");
    }
    assert_eq!(plan[0]["paths"]["finite"], 16);
    let realizations = d["realizations"].as_array().unwrap();
    // Every combination of the K3,3s' candidates is there, each assembled.
    let offered = |k: usize| plan[k]["offered"].as_u64().unwrap();
    for a in 0..offered(0) {
        for b in 0..offered(1) {
            assert!(
                realizations.iter().any(|r| r["choices"][0] == a && r["choices"][1] == b),
                "{a} {b}"
            );
        }
    }
    assert!(realizations.iter().all(|r| r["max_residual"].as_f64().unwrap() <= 1e-9));
    assert_eq!(
        realizations[d["autosolve"].as_u64().unwrap() as usize]["choices"],
        serde_json::json!([0, 0, 0])
    );
}

/// With the listing cut short (`--max-solutions 1` of the chain's 8), every candidate of every
/// step that some realization takes is still taken by one of the page (each one solve with
/// that choice), each satisfying every constraint.
#[test]
fn a_truncated_listing_still_offers_every_candidate() {
    let pairs = |d: &Value| -> std::collections::BTreeSet<(usize, u64)> {
        let mut out = std::collections::BTreeSet::new();
        for r in d["realizations"].as_array().unwrap() {
            for (c, k) in r["choices"].as_array().unwrap().iter().enumerate() {
                out.insert((c, k.as_u64().unwrap()));
            }
        }
        out
    };
    let page = |limit: &str| {
        let page = temp(&format!("chain_{limit}.html"));
        let out = page.to_str().unwrap();
        let args = ["navigate", "data/paper/chain.ron", "--max-solutions", limit, "-o", out];
        let (code, _, err) = gcs(&args);
        assert_eq!(code, 0, "{err}");
        embedded(&std::fs::read_to_string(&page).unwrap())
    };
    let (all, cut) = (page("256"), page("1"));
    assert_eq!((&all["truncated"], &cut["truncated"]), (&Value::from(false), &Value::from(true)));
    let cut_realizations = cut["realizations"].as_array().unwrap();
    assert!(cut_realizations.len() > 1, "{}", cut_realizations.len());
    assert!(cut_realizations.len() < all["realizations"].as_array().unwrap().len());
    // Steps 1 to 4 are closed-form steps with a choice; one of them has one candidate left.
    assert_eq!(pairs(&cut), pairs(&all));
    assert!(pairs(&all).len() >= 8, "{:?}", pairs(&all));
    assert!(cut_realizations.iter().all(|r| r["max_residual"].as_f64().unwrap() <= 1e-9));
}

#[test]
fn a_cad_file_opens_and_a_missing_sketch_is_named() {
    let page = temp("slot.html");
    // (The core as solved: its homotopy, 512 paths, is `gcs solve --all`'s business.)
    let (code, _, err) =
        gcs(&["navigate", "data/cad/slot.slvs", "--max-paths", "0", "-o", page.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let d = embedded(&std::fs::read_to_string(&page).unwrap());
    assert_eq!(d["model"], "slot/g2");
    assert!(!d["realizations"].as_array().unwrap().is_empty());
    let (code, _, err) =
        gcs(&["navigate", "data/cad/slot.slvs", "--sketch", "nope", "-o", page.to_str().unwrap()]);
    assert_eq!(code, 1);
    assert!(err.contains("no sketch named \"nope\"") && err.contains("slot/g2"), "{err}");
}

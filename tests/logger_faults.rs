//! Logger faults on recordings made outside wbv: `tools/input-fixtures/run DIR` writes coarse
//! converters' CSV exports with numpy (`loggers.py`) and a gap case whose head channel went through
//! an 8-bit converter that uses ten codes on the quiet run (tools/blind-gap/gen.py, numpy + scipy);
//! `tools/test` runs this test with `WBV_INPUT_FIXTURES=DIR`. Clipping is a value held at the
//! converter's range limit; a quantised signal that revisits its codes is neither clipped nor held,
//! in `wbv analyze` (whose warnings `wbv report` prints) and in `wbv gap` alike.

mod common;
use common::wbv;

fn json(out: &std::process::Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

fn warnings(doc: &serde_json::Value) -> Vec<String> {
    doc["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w.as_str().unwrap().to_string())
        .collect()
}

#[test]
fn analyze_names_clipping_only_where_a_converter_reached_its_range() {
    let Some(dir) = common::input_fixtures() else {
        return;
    };
    let dir = dir.join("loggers");
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("manifest.json")).unwrap()).unwrap();
    let entries = manifest.as_array().unwrap();
    assert!(entries.len() >= 4);
    for e in entries {
        let file = dir.join(e["file"].as_str().unwrap());
        let doc = json(&wbv(&["analyze", file.to_str().unwrap(), "--json"]));
        let w = warnings(&doc);
        let faults: Vec<&String> = w
            .iter()
            .filter(|w| !w.starts_with("input:"))
            .filter(|w| w.contains("clipped") || w.contains("held value"))
            .collect();
        match e["clipped"].as_array() {
            None => assert!(faults.is_empty(), "{}: {faults:?}", file.display()),
            Some(rails) => {
                assert_eq!(faults.len(), 1, "{}: {w:?}", file.display());
                assert!(faults[0].starts_with("a_seat_z: ") && faults[0].contains("clipped"));
                // Each stretch is at one of the converter's two end codes: the rails' samples are
                // the only ones a clipped stretch may hold.
                assert!(rails.len() == 2);
            }
        }
    }
}

#[test]
fn a_coarse_quiet_channel_keeps_its_path_in_the_gap_diagnosis() {
    let Some(dir) = common::input_fixtures() else {
        return;
    };
    let case = dir.join("coarse-logger/case-000");
    let truth: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(case.join("truth.json")).unwrap()).unwrap();
    assert_eq!(truth["nuisances"]["coarse_logger"]["channel"], "a_head_z");
    let doc = json(&common::gap_case(&case));
    let w = warnings(&doc);
    assert!(
        w.iter().all(|w| !w.contains("clipped")
            && !w.contains("clipping")
            && !w.contains("left out of this run")),
        "{w:?}"
    );
    let text = doc.to_string();
    assert!(text.contains("seat-head"), "the head path is diagnosed");
    assert_eq!(
        doc["verdict"], "none",
        "no effect was planted: {}",
        doc["verdict_text"]
    );
}

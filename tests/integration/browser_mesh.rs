//! The mesh export of the editor and the static site (issue 33, item 3):
//! a 3D input's GLB button writes what `stlc render --mesh glb --unit U`
//! writes, byte for byte, from `stlc serve` (HTTP) and from the
//! WebAssembly engine; the unit is a control beside it, the view's
//! angles a label, and the command line shown says `--unit`. Screenshots
//! go to `tests/store/browser/mesh-*.png`.

use serde_json::json;

use super::browser_steps::{set_value, text_of};
use super::browser_web::{engine_export, on_site, open_example};
use super::chromium::{cli_line, click, downloaded, js, on_served_page, same_bytes, shot};
use super::serve::{Server, example, post};
use crate::support::numbers;

/// `stlc render examples/NAME --mesh glb --unit UNIT -o -`.
fn cli_glb(name: &str, unit: &str) -> Vec<u8> {
    cli_line(&format!("render examples/{name} --mesh glb --unit {unit}"))
}

/// The `max` of a glb's first POSITION accessor: the mesh's extent, in
/// metres.
fn position_max(glb: &[u8]) -> Vec<f64> {
    assert_eq!(&glb[..4], b"glTF");
    let n = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let gltf: serde_json::Value = serde_json::from_slice(&glb[20..20 + n]).unwrap();
    let at = gltf["meshes"][0]["primitives"][0]["attributes"]["POSITION"]
        .as_u64()
        .unwrap();
    let at = at as usize;
    numbers(&gltf["accessors"][at]["max"])
}

#[test]
fn a_glb_export_over_http_is_the_cli_mesh_at_the_unit_asked() {
    let server = Server::start(&[]);
    let text = example("hilbert3d.lsys");
    let glb = |unit: serde_json::Value| {
        let body = json!({"source": text, "kind": "lsys", "unit": unit});
        post(&server.addr, "/api/export?format=glb", &[], &body)
    };
    let at2 = glb(json!(0.02));
    let head = &at2.head;
    assert!(head.contains("content-type: model/gltf-binary"), "{head}");
    let cli = cli_glb("hilbert3d.lsys", "0.02");
    same_bytes(&at2.body, &cli, "hilbert3d.glb");
    // No unit: the CLI's default, 0.01 m a unit; twice the unit, twice the
    // mesh (Hilbert's cube is the same shape at any unit).
    let at1 = glb(serde_json::Value::Null);
    let cli = cli_glb("hilbert3d.lsys", "0.01");
    same_bytes(&at1.body, &cli, "default unit");
    let (a, b) = (position_max(&at1.body), position_max(&at2.body));
    for (x, y) in a.iter().zip(&b) {
        assert!((2.0 * x - y).abs() < 1e-5, "{a:?} then {b:?}");
    }
    // A unit that is no length is refused, naming the field.
    for bad in [json!(0), json!(-1)] {
        let r = glb(bad);
        assert!(r.head.starts_with("http/1.1 400"), "{}", r.head);
        let body = String::from_utf8_lossy(&r.body).into_owned();
        assert!(body.contains("`unit`"), "{body}");
    }
}

/// The editor's GLB button: shown for a 3D input only, beside the unit
/// and the view's angles; the file it downloads is the CLI's.
#[test]
fn the_editor_exports_a_3d_input_as_the_cli_glb_in_chromium() {
    on_served_page(async |c, served| {
        let shown = "return document.getElementById('export-glb').getClientRects().length > 0";
        // The paper's 2D tree has no mesh to export.
        assert_eq!(js(c, shown).await, json!(false));
        open_example(c, "hilbert3d.lsys").await;
        assert_eq!(js(c, shown).await, json!(true));
        let view = "view 30°, 20° (PNG, SVG); the mesh: y up, root at the origin";
        assert_eq!(text_of(c, "#mesh-view").await, view);
        set_value(c, "#mesh-unit", "0.02").await;
        click(c, "#export-options summary").await;
        let command = text_of(c, "#export-cli").await;
        let line = "stlc render hilbert3d.lsys --mesh glb --unit 0.02 -o hilbert3d.glb";
        assert!(command.lines().any(|l| l == line), "{command}");
        shot(c, "mesh-01-export").await;
        click(c, "#export-glb").await;
        let got = downloaded(&served.downloads, "hilbert3d.glb").await;
        same_bytes(&got, &cli_glb("hilbert3d.lsys", "0.02"), "hilbert3d.glb");
    });
}

/// The static site's engine (WebAssembly) writes the same mesh.
#[test]
fn the_static_site_exports_the_cli_glb_in_chromium() {
    on_site(async |c, _, _| {
        open_example(c, "hilbert3d.lsys").await;
        let text = example("hilbert3d.lsys");
        let request = json!({"source": text, "kind": "lsys", "unit": 0.02});
        let got = engine_export(c, &request, "glb").await.unwrap();
        same_bytes(&got, &cli_glb("hilbert3d.lsys", "0.02"), "hilbert3d.glb");
        shot(c, "mesh-02-web").await;
    });
}

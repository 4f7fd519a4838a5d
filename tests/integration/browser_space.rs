//! Space-first growth in the browser (issue 34): the static site's
//! engine grows the CLI's BED byte for byte, and the editor's growth
//! control offers `space`, writes `O=space` into the text and draws what
//! the CLI draws of that text; with a seed `V=` in the file too.

use serde_json::json;

use super::browser_steps::shows_svg;
use super::browser_web::{engine_export, on_site, open_example};
use super::chromium::{cli, cli_svg_of, click, same_bytes, settled_until, shot};
use super::serve::example;

#[test]
fn the_web_engine_and_the_growth_control_grow_space_first_as_the_cli_in_chromium() {
    on_site(async |c, _, _| {
        // The engine: the same BED as `stlc compile --growth space`, for
        // an outline with holes and one grown into a forest of trees.
        for name in ["holes.od", "grove.od"] {
            let request = json!({"source": example(name), "growth": "space"});
            let bed = engine_export(c, &request, "bed").await.unwrap();
            let path = format!("examples/{name}");
            same_bytes(&bed, &cli(&["compile", &path, "--growth", "space"]), name);
        }
        // A seed in the file (`V=`, which moves the attraction points):
        // the engine's BED is still the CLI's.
        let text = example("holes.od").replace("C=1.5\n", "C=1.5 V=5\n");
        assert!(text.contains("V=5"));
        let path = std::env::temp_dir().join(format!("stlc-space-v5-{}.od", std::process::id()));
        std::fs::write(&path, &text).unwrap();
        let request = json!({"source": text, "growth": "space"});
        let bed = engine_export(c, &request, "bed").await.unwrap();
        let p = path.to_str().unwrap();
        let want = cli(&["compile", p, "--growth", "space"]);
        same_bytes(&bed, &want, "holes.od V=5");
        let without_v = cli(&["compile", "examples/holes.od", "--growth", "space"]);
        assert_ne!(bed, without_v);
        std::fs::remove_file(&path).ok();
        // The control: choosing space writes the key into the text, and
        // the picture is the CLI's of that text.
        open_example(c, "holes.od").await;
        click(c, "#growth option[value=space]").await;
        let space = |v: &serde_json::Value| v["text"].as_str().unwrap().contains("O=space");
        let v = settled_until(c, 100, 50, space).await;
        let text = v["text"].as_str().unwrap().to_string();
        assert!(text.contains("O=space"), "{text}");
        let want = cli_svg_of("holes.od", &text);
        shows_svg(c, &want, "the editor's space-first holes.od").await;
        shot(c, "space-01-growth-control").await;
    });
}

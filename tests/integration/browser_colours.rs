//! The colour controls in a real Chromium (issue 33, item 6): the stem
//! colour field rewrites only an OD's `S=` key (an .lsys's `color`), each
//! palette field only its colour's word of the `palette` line, and `+`
//! adds one; the picture is the CLI's for the new text. Screenshots go to
//! `tests/store/browser/colours-*.png`.

use serde_json::{Value, json};

use super::browser_steps::{answer_svg, count, set_value, value_of};
use super::browser_web::open_example;
use super::chromium::{
    answered, cli_svg_of, click, js, on_served_page, same_bytes, settled_until, shot,
};
use super::serve::example;

/// Sets the colour field `css` to `hex` as a pick does (an `input`
/// event); the page's answer once its text is `want`.
async fn pick(c: &fantoccini::Client, css: &str, hex: &str, want: &str) -> Value {
    set_value(c, css, hex).await;
    answered(c, want, &format!("with {hex} from {css}")).await
}

/// The lines of `a` and `b` that differ (same number of lines).
fn changed_lines(a: &str, b: &str) -> Vec<(String, String)> {
    let (x, y): (Vec<&str>, Vec<&str>) = (a.lines().collect(), b.lines().collect());
    assert_eq!(x.len(), y.len());
    let pairs = x.iter().zip(&y).filter(|(p, q)| p != q);
    pairs.map(|(p, q)| (p.to_string(), q.to_string())).collect()
}

#[test]
fn the_stem_colour_and_palette_fields_rewrite_only_their_key_in_chromium() {
    on_served_page(async |c, _| {
        // The paper's 2DTree has no S=: the field shows the colour drawn,
        // and a pick adds ` S=#8b4513` at the header's end, nothing else.
        open_example(c, "2dtree.od").await;
        let paper = example("2dtree.od");
        let stroke = js(c, "return window.stlc.state.answer.stroke").await;
        // The paper's brown, as the CLI draws it (not the field's default black).
        assert_eq!(stroke, json!("#4a2c12"));
        assert_eq!(value_of(c, "#stem-colour").await, stroke);
        let brown = paper.replace("B=1(0)RULE", "B=1(0) S=#8b4513 RULE");
        assert_ne!(brown, paper);
        pick(c, "#stem-colour", "#8b4513", &brown).await;
        assert_eq!(changed_lines(&paper, &brown).len(), 1);
        let want = cli_svg_of("2dtree.od", &brown);
        same_bytes(answer_svg(c).await.as_bytes(), &want, "brown 2dtree");
        assert!(String::from_utf8_lossy(&want).contains("#8b4513"));
        // Picked again: the key's value changes, not the key added twice.
        let darker = paper.replace("B=1(0)RULE", "B=1(0) S=#5b3a1e RULE");
        pick(c, "#stem-colour", "#5b3a1e", &darker).await;

        // Fig. 1.26's palette: a field per colour, each the line's.
        open_example(c, "abop-1.26.lsys").await;
        let plant = example("abop-1.26.lsys");
        let script =
            "return [...document.querySelectorAll('#palette-colours input')].map((f) => f.value)";
        let fields = js(c, script).await;
        assert_eq!(fields, json!(["#2f5d1e", "#4f9a34", "#e9679b", "#f2c230"]));
        let before = "palette #2f5d1e #4f9a34 #e9679b #f2c230".to_string();
        let after = "palette #2f5d1e #4f9a34 #7b2cbf #f2c230".to_string();
        let petals = plant.replace(&before, &after);
        pick(c, "[data-testid=palette-2]", "#7b2cbf", &petals).await;
        assert_eq!(changed_lines(&plant, &petals), [(before, after)]);
        // `+` adds a copy of the last colour to the line, a fifth field.
        click(c, "[data-testid=palette-add]").await;
        let five = petals.replace("#7b2cbf #f2c230", "#7b2cbf #f2c230 #f2c230");
        let added = settled_until(c, 100, 50, |v| v["text"] == json!(five)).await;
        assert_eq!(added["text"], json!(five));
        assert_eq!(count(c, "#palette-colours input").await, 5);
        shot(c, "colours-01-palette").await;
    });
}

//! The editor never loses an edit, tried in a real Chromium as a user
//! would: save and reload; unsaved edits kept across a reload and offered
//! back; a change on disk loaded by itself; two tabs on one file, where
//! the second Save is refused and nothing is lost.

use std::path::Path;
use std::time::Duration;

use fantoccini::Client;

use super::browser_steps::{
    assign_value, count, editor_text, reload, set_checked, set_value, settled_ok, text_of,
    texts_of, type_into, until_shown, value_of,
};
use super::chromium::{
    Served, cli_line, click, downloaded, js, on_served_file, open, settled, shot, until,
};
use super::serve::example;
use crate::support::manifest_path;

#[test]
fn no_edit_is_lost_across_reloads_tabs_and_disk_changes_in_chromium() {
    on_served_file(
        "r2.od",
        &example("fig9.od"),
        async |c, served: &Served<'_>| {
            let file = served.file;
            reload_keeps_saves_and_drafts(c, file).await;
            disk_changes_are_loaded(c, file).await;
            two_tabs(c, &served.server.url, file).await;
            exact_counts(c).await;
            long_work_is_cancelled(c, served.server).await;
            a_failing_file_shows_no_other_picture(c, served.dir).await;
            new_from_a_template_or_an_example(c).await;
            export_as_artists_need(c, &served.downloads).await;
            replay_steps_and_speeds(c).await;
            settings_are_keys_in_the_text(c).await;
            words_generation_by_generation(c).await;
            numbers_scrub(c).await;
            main_thread_stalls(c).await;
            a_rule_that_never_fits_says_why(c).await;
        },
    );
}

/// Types `line` at the end of the text, as keys.
async fn type_line(c: &Client, line: &str) {
    let src = c.find(fantoccini::Locator::Css("#source")).await.unwrap();
    src.click().await.unwrap();
    js(c, "const s = document.getElementById('source'); s.selectionStart = s.selectionEnd = s.value.length;").await;
    src.send_keys(line).await.unwrap();
}

/// Clicks Save and waits until the page says the file is saved.
async fn save(c: &Client, what: &str) {
    click(c, "[data-testid=save]").await;
    let saved = "return document.getElementById('saved').textContent.startsWith('Saved')";
    until(c, saved, what).await;
}

async fn status(c: &Client) -> String {
    text_of(c, "#saved").await
}

async fn title(c: &Client) -> String {
    c.title().await.unwrap()
}

async fn reload_keeps_saves_and_drafts(c: &Client, file: &Path) {
    // Problem 1: add a line, Save, reload: the page shows the file as saved.
    type_line(c, "\n# saved line").await;
    let unsaved = title(c).await.starts_with("• ");
    assert!(unsaved, "unsaved edits are in the title");
    assert_eq!(status(c).await, "Unsaved changes");
    save(c, "saved").await;
    assert!(!title(c).await.starts_with("• "));
    assert!(on_disk(file).ends_with("# saved line"));
    reload(c).await;
    let shown = editor_text(c).await;
    assert!(shown.ends_with("# saved line"), "the reload shows the save");

    // Unsaved edits survive a reload: offered back, not applied.
    type_line(c, "\n# not saved yet").await;
    tokio::time::sleep(Duration::from_millis(600)).await;
    reload(c).await;
    let t = editor_text(c).await;
    let silently = "a draft is never applied silently";
    assert!(t.ends_with("# saved line"), "{silently}");
    until_shown(c, "notice", "the draft is offered").await;
    shot(c, "30-draft-offered").await;
    click(c, "[data-testid=restore-draft]").await;
    assert!(editor_text(c).await.ends_with("# not saved yet"));
    assert!(title(c).await.starts_with("• "));
    // Saved, so there is nothing left to offer.
    save(c, "saved again").await;
    assert!(on_disk(file).ends_with("# not saved yet"));
}

async fn disk_changes_are_loaded(c: &Client, file: &Path) {
    // No unsaved edits: another program's write is loaded by itself.
    let mut theirs = std::fs::read_to_string(file).unwrap();
    theirs.push_str("\n# from another program");
    std::fs::write(file, &theirs).unwrap();
    let script =
        "return document.getElementById('source').value.endsWith('# from another program')";
    until(c, script, "the disk change is loaded").await;
    let said = status(c).await;
    assert!(said.starts_with("Reloaded"), "{said}");

    // With unsaved edits: asked, and keeping mine then saving writes mine.
    type_line(c, "\n# mine").await;
    theirs.push_str("\n# theirs again");
    std::fs::write(file, &theirs).unwrap();
    until_shown(c, "notice", "the change is asked about").await;
    let mine = editor_text(c).await;
    assert!(mine.ends_with("# mine"), "unsaved edits stay");
    shot(c, "31-disk-changed").await;
    click(c, "[data-testid=keep-mine]").await;
    save(c, "mine saved").await;
    let on_disk = std::fs::read_to_string(file).unwrap();
    assert!(on_disk.ends_with("# mine") && !on_disk.contains("# theirs again"));
}

async fn two_tabs(c: &Client, url: &str, file: &Path) {
    // Tab one has an unsaved edit when tab two saves.
    type_line(c, "\n# tab one").await;
    let first = c.window().await.unwrap();
    let second = c.new_window(true).await.unwrap();
    c.switch_to_window(second.handle).await.unwrap();
    c.goto(url).await.unwrap();
    settled(c).await;
    type_line(c, "\n# tab two").await;
    save(c, "tab two saved").await;

    // Tab one's edit is of the older version: its Save is refused.
    c.switch_to_window(first).await.unwrap();
    click(c, "[data-testid=save]").await;
    // (The watch may have asked about the change already; the refused
    // Save's notice replaces it.)
    let script = "const n = document.getElementById('notice'); return !n.hidden && n.textContent.includes('changed since')";
    until(c, script, "the conflict is shown").await;
    let notice = text_of(c, "#notice").await;
    assert!(notice.contains("changed since"), "{notice}");
    let overwritten = "the second save did not overwrite the first";
    assert!(on_disk(file).ends_with("# tab two"), "{overwritten}");
    let lost = "nothing is lost in the editor";
    assert!(editor_text(c).await.ends_with("# tab one"), "{lost}");
    // Both side by side.
    click(c, "[data-testid=compare]").await;
    assert!(text_of(c, "#compare-theirs").await.ends_with("# tab two"));
    assert!(text_of(c, "#compare-mine").await.ends_with("# tab one"));
    shot(c, "32-two-tabs-compare").await;
    click(c, "[data-testid=keep-mine]").await;
    save(c, "tab one saved").await;
    assert!(on_disk(file).ends_with("# tab one"));
}

/// Problem 6: abop-1.24a at depth 30 has 5^30 segments, more than a u64
/// (and far more than a JavaScript number holds exactly): the status shows
/// every digit, grouped by threes.
async fn exact_counts(c: &Client) {
    open(c, &manifest_path("examples/abop-1.24a.lsys")).await;
    settled(c).await;
    set_depth(c, "30").await;
    let script = "return document.getElementById('status').textContent.includes('931,322,574,615,478,515,625 stems')";
    until(c, script, "the exact count is shown").await;
}

/// Problem 5: tests/cases/render/slow-stochastic.lsys at depth 14 takes
/// many seconds (12 s in a release build; ABOP 1.27 did before it drew at
/// a level of detail); the busy indicator shows with Cancel, and an edit
/// back to depth 5 cancels the long work (the server stops it) and shows
/// its picture within a second or two.
async fn long_work_is_cancelled(c: &Client, server: &super::serve::Server) {
    open(c, &manifest_path("tests/cases/render/slow-stochastic.lsys")).await;
    settled(c).await;
    // Problem 4: the last file's depth (30) does not follow to this one:
    // the control shows this file's own `generations`.
    let depth = value_of(c, "#depth").await;
    assert_eq!(depth, "5", "the depth of the file before leaked");
    let stems = js(c, "return window.stlc.state.answer.stems").await;
    // 1 + (4^5 - 1) / 3 segments, whatever the choices.
    assert_eq!(stems, "342", "drawn at its own generations (5)");
    set_depth(c, "14").await;
    until_shown(c, "busy", "the busy indicator shows").await;
    shot(c, "33-busy").await;
    let t0 = std::time::Instant::now();
    set_depth(c, "5").await;
    let script = "const s = window.stlc.state; return !s.inFlight && s.answer && s.answer.ok && s.answer.stems === '342'";
    until(c, script, "the depth-5 picture").await;
    let took = t0.elapsed();
    assert!(
        // The depth-14 work alone takes about 15 s: the picture of depth 5
        // comes long before it would have ended (a loose bound, for busy
        // CI machines; measured here well under 3 s).
        took < Duration::from_secs(10),
        "the new picture took {took:?}"
    );
    // The depth-14 work stopped on the server: its CPU time no longer rises.
    tokio::time::sleep(Duration::from_millis(500)).await;
    let t1 = server.cpu_ticks();
    tokio::time::sleep(Duration::from_millis(1000)).await;
    let t2 = server.cpu_ticks();
    let went_on = format!("the cancelled work went on: {t1} -> {t2} ticks");
    assert!(t2 - t1 <= 10, "{went_on}");
    // Cancel: the work stops and the last picture stays.
    set_depth(c, "14").await;
    until_shown(c, "busy", "busy again").await;
    click(c, "[data-testid=cancel]").await;
    let script = "return document.getElementById('busy').hidden && document.getElementById('status').textContent.startsWith('Cancelled')";
    until(c, script, "cancelled").await;
}

/// Types `value` into the emptied depth field.
async fn set_depth(c: &Client, value: &str) {
    let depth = c.find(fantoccini::Locator::Id("depth")).await.unwrap();
    depth.click().await.unwrap();
    assign_value(c, "#depth", "").await;
    depth.send_keys(value).await.unwrap();
}

/// Problem 4: a file opened that fails shows no picture of the file
/// before it (its errors, and an empty preview).
async fn a_failing_file_shows_no_other_picture(c: &Client, dir: &Path) {
    let broken = dir.join("broken.lsys");
    let text = "generations 3\naxiom F\nangle 30\nrule F -> F[+F\n";
    std::fs::write(&broken, text).unwrap();
    open(c, &broken).await;
    let script =
        "const s = window.stlc.state; return !s.inFlight && s.answer && s.answer.ok === false";
    until(c, script, "the broken file's answer").await;
    let pictures = count(c, "#preview .lib").await;
    assert_eq!(pictures, 0, "the last file's picture is still shown");
    let status = text_of(c, "#status").await;
    assert!(status.contains("no picture of this file yet"), "{status}");
    shot(c, "34-broken-file-no-picture").await;
}

/// New: a template or any example opens as a new document (problem 10):
/// the `.od` template grows a tree, an example is its file's text.
async fn new_from_a_template_or_an_example(c: &Client) {
    let names = texts_of(c, "#new option").await;
    assert!(names.iter().any(|n| n == "new.od (template)"), "{names:?}");
    assert!(names.iter().any(|n| n == "hilbert.lsys"), "{names:?}");
    click(c, "#new option[value='0']").await;
    let grown = settled_ok(c).await;
    assert!(grown["stems"].as_u64().unwrap() > 50, "{grown}");
    new_from(c, "hilbert.lsys").await;
    let drawn = settled_ok(c).await;
    assert_eq!(drawn["text"].as_str().unwrap(), example("hilbert.lsys"));
    shot(c, "35-new-from-example").await;
}

/// Problem 10 / item 8: a tree-only, transparent PNG at a chosen size is
/// the CLI's bytes for the command the page shows.
async fn export_as_artists_need(c: &Client, downloads: &Path) {
    new_from(c, "2dtree.od").await;
    settled(c).await;
    click(c, "#export-options summary").await;
    set_value(c, "#export-w", "300").await;
    set_value(c, "#export-h", "200").await;
    set_checked(c, "#export-layout", false).await;
    set_checked(c, "#export-transparent", true).await;
    let shown = text_of(c, "#export-cli").await;
    let want = "stlc render 2dtree.od --size 300x200 --background none -o 2dtree.png";
    assert!(shown.contains(want), "{shown}");
    shot(c, "36-export-options").await;
    click(c, "#export-png").await;
    let got = downloaded(downloads, "2dtree.png").await;
    let want = cli_line("render examples/2dtree.od --size 300x200 --background none");
    assert!(got == want, "the export is not the CLI's bytes");
    let png = tiny_skia::Pixmap::decode_png(&got).unwrap();
    assert_eq!((png.width(), png.height()), (300, 200));
    let alpha = png.pixel(0, 0).unwrap().alpha();
    assert_eq!(alpha, 0, "the background is transparent");
    // A coloured background instead.
    set_checked(c, "#export-transparent", false).await;
    set_checked(c, "#export-coloured", true).await;
    set_value(c, "#export-colour", "#336699").await;
    let shown = text_of(c, "#export-cli").await;
    let want = "--size 300x200 --background '#336699' -o 2dtree.png";
    assert!(shown.contains(want), "{shown}");
    click(c, "#export-png").await;
    let got = downloaded(downloads, "2dtree (1).png").await;
    let want = cli_line("render examples/2dtree.od --size 300x200 --background #336699");
    assert!(got == want, "the coloured export is not the CLI's bytes");
    let png = tiny_skia::Pixmap::decode_png(&got).unwrap();
    let p = png.pixel(0, 0).unwrap();
    let rgba = (p.red(), p.green(), p.blue(), p.alpha());
    assert_eq!(rgba, (0x33, 0x66, 0x99, 255));
}

/// Teaching (item 9): the replay steps one decision back and on, and plays
/// one decision a frame when asked (144 decisions of 2DTree: about 5 s).
async fn replay_steps_and_speeds(c: &Client) {
    for (button, want) in [
        (None, "decision 144 of 144"),
        (Some("step-back"), "decision 143 of 144"),
        (Some("step-back"), "decision 142 of 144"),
        (Some("step-next"), "decision 143 of 144"),
    ] {
        if let Some(id) = button {
            click(c, &format!("[data-testid={id}]")).await;
        }
        let label = text_of(c, "#step-label").await;
        assert!(label.starts_with(want), "{label}");
    }
    assign_value(c, "#replay-speed", "1").await;
    assign_value(c, "#step", "0").await;
    click(c, "[data-testid=play]").await;
    tokio::time::sleep(Duration::from_millis(1000)).await;
    let at: u64 = value_of(c, "#step").await.parse().unwrap();
    let one_a_frame = format!("one decision a frame: at {at} after a second");
    assert!(at > 0 && at < 144, "{one_a_frame}");
    click(c, "[data-testid=play]").await;
    shot(c, "37-replay-step").await;
}

/// Item 2: the controls edit keys in the text (only that key), and typing
/// a key moves its control.
async fn settings_are_keys_in_the_text(c: &Client) {
    new_from(c, "fig9.od").await;
    let before = settled(c).await;
    let fig9 = before["text"].as_str().unwrap().to_string();
    click(c, "#growth option[value=dfs]").await;
    let dfs = settled(c).await;
    let want = fig9.replace("A=30 C=2\n", "A=30 C=2 O=dfs\n");
    assert_eq!(dfs["text"].as_str().unwrap(), want);
    assert_ne!(dfs["growth"], before["growth"], "O=dfs grows another tree");
    // Typing the key back moves the control.
    let bfs = editor_text(c).await.replace("O=dfs", "O=bfs");
    set_value(c, "#source", &bfs).await;
    let typed = settled(c).await;
    assert_eq!(typed["growth"], before["growth"]);
    assert_eq!(value_of(c, "#growth").await, "bfs");
    // The seed control writes V=, and emptying it removes the key.
    type_into(c, "seed", "7").await;
    let with_seed = settled(c).await["text"].as_str().unwrap().to_string();
    assert!(with_seed.contains("O=bfs V=7\n"), "{with_seed}");
    set_value(c, "#seed", "").await;
    let without = settled(c).await["text"].as_str().unwrap().to_string();
    assert!(!without.contains("V="), "{without}");
}

/// Teaching (problem 11): an .lsys's word, generation by generation, as
/// `stlc expand --depth N` writes it, with its exact length.
async fn words_generation_by_generation(c: &Client) {
    new_from(c, "koch-snowflake.lsys").await;
    settled(c).await;
    click(c, "#words summary").await;
    let script = "return document.querySelectorAll('#word-list li').length === 5";
    until(c, script, "five generations").await;
    let items = texts_of(c, "#word-list li").await;
    let koch = manifest_path("examples/koch-snowflake.lsys");
    for (depth, item) in items.iter().enumerate() {
        let word = cli_line(&format!("expand {} --depth {depth}", koch.display()));
        let word = String::from_utf8(word).unwrap();
        let word = word.trim_end();
        assert_eq!(*item, format!("{word} ({})", word.len()), "depth {depth}");
    }
    shot(c, "38-words").await;
}

/// Teaching (item 9): a header number scrubbed with its slider rewrites
/// only that number, and the tree regrows.
async fn numbers_scrub(c: &Client) {
    new_from(c, "fig9.od").await;
    let before = settled(c).await;
    click(c, "#scrub summary").await;
    let script = "return document.querySelector('#scrub-list input[data-key=A]') !== null";
    until(c, script, "the A slider").await;
    set_value(c, "#scrub-list input[data-key=A]", "45").await;
    let after = settled(c).await;
    let want = before["text"].as_str().unwrap().replace("A=30", "A=45");
    assert_eq!(after["text"].as_str().unwrap(), want);
    assert_ne!(after["growth"], before["growth"], "the tree regrew");
    shot(c, "39-numbers").await;
}

/// Item 3: the page stays responsive: the longest main-thread task while
/// grove.od (1,947 stems) is edited and redrawn five times, measured with
/// the browser's long-task timing (tasks over 50 ms), is printed; it must
/// stay under eight times a fixed piece of JavaScript (ten million square
/// roots) timed on the same main thread before and after, the slower of
/// the two (about 25 ms on an idle machine, so about 200 ms: growth on
/// the page's thread, or a redraw per stem, takes several times that).
/// A ratio measured side by side, so a loaded machine slows both; and the
/// best of three rounds, since a task the machine's load stretched (other
/// tests' browsers and builds beside this one) is not the page's: a page
/// that stalls stalls in every round.
async fn main_thread_stalls(c: &Client) {
    new_from(c, "grove.od").await;
    settled(c).await;
    let observe = "window.__longest = 0; new PerformanceObserver((l) => { for (const e of l.getEntries()) window.__longest = Math.max(window.__longest, e.duration); }).observe({type: 'longtask', buffered: false}); return 0;";
    js(c, observe).await;
    let mut rounds = Vec::new();
    for round in 0..3 {
        let unit = js_unit(c).await;
        js(c, "window.__longest = 0; return 0").await;
        for k in 0..5 {
            let text = editor_text(c).await;
            set_value(c, "#source", &format!("{text}\n# {round}.{k}")).await;
            settled(c).await;
        }
        let longest = js(c, "return window.__longest").await.as_f64().unwrap();
        let unit = unit.max(js_unit(c).await);
        let units = longest / unit;
        eprintln!(
            "longest main-thread task while editing grove.od: {longest:.0} ms ({units:.1} units of {unit:.0} ms)"
        );
        rounds.push(format!(
            "{longest:.0} ms, {units:.1} times the {unit:.0} ms unit"
        ));
        if longest < 8.0 * unit {
            return;
        }
    }
    panic!("a stall in every round: {rounds:?}");
}

/// The median of three timings, in ms, of ten million square roots on the
/// page's main thread: the unit [`main_thread_stalls`] measures in.
async fn js_unit(c: &Client) -> f64 {
    let roots = "const t = []; for (let r = 0; r < 3; r++) { const t0 = performance.now(); let s = 0; for (let i = 0; i < 1e7; i++) s += Math.sqrt(i); window.__sink = s; t.push(performance.now() - t0); } t.sort((a, b) => a - b); return t[1];";
    js(c, roots).await.as_f64().unwrap()
}

/// Problem 8 in the page: a rule that never fits is a warning at its line
/// with the distances and a hint.
async fn a_rule_that_never_fits_says_why(c: &Client) {
    let od = "Problem8\n(150, 290)\nL=9(0.3) B=3(0.3) A=25 C=1.5\nRULE\nR1: F[+F][-F][F]\nSEED\nFFFFFFFFF R1\nENDSEED\nLAYOUT\n(clGreen) Rectangle (0, 0), 300, 300\nENDLAYOUT\n";
    set_value(c, "#source", od).await;
    settled_ok(c).await;
    let warning = text_of(c, "[data-testid=diagnostics] li").await;
    let distances = warning.contains("3.677") && warning.contains("4.2");
    assert!(warning.contains("never grew") && distances, "{warning}");
    assert!(warning.contains("raise `A`"), "{warning}");
    // The Numbers panel follows the text typed.
    let shown = text_of(c, "#scrub-list input[data-key=A] + output").await;
    assert_eq!(shown, "25");
    shot(c, "40-never-fitted").await;
}

/// Opens the template or example `name` from the New… menu.
async fn new_from(c: &Client, name: &str) {
    let names = texts_of(c, "#new option").await;
    let at = names.iter().position(|n| n == name);
    let i = at.unwrap_or_else(|| panic!("{name} is not in New…: {names:?}")) - 1;
    click(c, &format!("#new option[value='{i}']")).await;
}

/// The text of `file` on disk.
fn on_disk(file: &Path) -> String {
    std::fs::read_to_string(file).unwrap()
}

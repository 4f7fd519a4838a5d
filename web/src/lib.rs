//! stlc in the browser: the pipeline as a WebAssembly module for the
//! static Tree Maker and the `<stl-tree>` element (docs/web.md).
//!
//! The module imports nothing and exports plain functions (no bindings
//! generator; docs/dependencies.md says why). A call goes:
//!
//! 1. `stlc_input(len)` makes the input buffer `len` bytes long and
//!    returns where it is; the JavaScript glue writes the request's JSON
//!    there (UTF-8);
//! 2. `stlc_render()`, `stlc_export(format)`, `stlc_words()`,
//!    `stlc_compile()` or `stlc_check()` runs the call and returns its
//!    [`calls::Status`] (0 done, 1 failed: JSON);
//! 3. `stlc_output()` and `stlc_output_len()` say where the answer's bytes
//!    are; the glue copies them out before the next call.
//!
//! Both buffers belong to the module, so the glue never allocates or frees
//! memory, and there is no `unsafe` block: only the exports' unmangled
//! names need `#[unsafe(no_mangle)]`.

pub mod calls;

use stlc::api::Format;

use std::cell::RefCell;

thread_local! {
    /// The request being written by the glue.
    static INPUT: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
    /// The last call's answer.
    static OUTPUT: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
}

/// Runs `call` on the input buffer and keeps its answer; returns its status.
///
/// A panic (a bug: the pipeline reports bad input as diagnostics) aborts
/// the module, which traps; before that, the panic hook puts
/// `{"ok": false, "error": "..."}` with the panic's message in the output
/// buffer, so the glue can say what happened. The buffer is emptied
/// first: after a trap, an empty one means the module stopped without a
/// message (memory exhausted).
fn run(call: impl FnOnce(&[u8]) -> calls::Answer) -> u32 {
    static HOOK: std::sync::Once = std::sync::Once::new();
    HOOK.call_once(|| {
        // The default hook still runs (it prints, where there is a place
        // to print: in native tests).
        let default = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            keep_panic(&info.to_string());
            default(info);
        }));
    });
    OUTPUT.with(|o| o.borrow_mut().clear());
    let input = INPUT.with(|i| std::mem::take(&mut *i.borrow_mut()));
    let (status, bytes) = call(&input);
    OUTPUT.with(|o| *o.borrow_mut() = bytes);
    status as u32
}

/// A panic's message as the failed answer, in the output buffer.
fn keep_panic(message: &str) {
    let error = format!("the work stopped on a bug in stlc: {message}");
    let json = format!(
        "{{\"ok\":false,\"error\":{}}}",
        serde_json::to_string(&error).unwrap_or_else(|_| "\"\"".into())
    );
    OUTPUT.with(|o| {
        if let Ok(mut o) = o.try_borrow_mut() {
            *o = json.into_bytes();
        }
    });
}

/// Makes the input buffer `len` bytes long (zeros) and returns its address.
#[allow(unsafe_code)]
#[unsafe(no_mangle)]
pub extern "C" fn stlc_input(len: usize) -> *mut u8 {
    INPUT.with(|i| {
        let mut i = i.borrow_mut();
        *i = vec![0; len];
        i.as_mut_ptr()
    })
}

/// The address of the last answer.
#[allow(unsafe_code)]
#[unsafe(no_mangle)]
pub extern "C" fn stlc_output() -> *const u8 {
    OUTPUT.with(|o| o.borrow().as_ptr())
}

/// The length of the last answer in bytes.
#[allow(unsafe_code)]
#[unsafe(no_mangle)]
pub extern "C" fn stlc_output_len() -> usize {
    OUTPUT.with(|o| o.borrow().len())
}

/// `POST /api/render` (see [`calls::render`]).
#[allow(unsafe_code)]
#[unsafe(no_mangle)]
pub extern "C" fn stlc_render() -> u32 {
    run(calls::render)
}

/// `POST /api/export?format=...`, `format` 0 PNG, 1 SVG, 2 BED, 3 GLB (see
/// [`calls::export`]).
#[allow(unsafe_code)]
#[unsafe(no_mangle)]
pub extern "C" fn stlc_export(format: u32) -> u32 {
    let format = match format {
        0 => Some(Format::Png),
        1 => Some(Format::Svg),
        2 => Some(Format::Bed),
        3 => Some(Format::Glb),
        _ => None,
    };
    run(|i| calls::export(i, format))
}

/// `POST /api/words` (see [`calls::words`]).
#[allow(unsafe_code)]
#[unsafe(no_mangle)]
pub extern "C" fn stlc_words() -> u32 {
    run(calls::words)
}

/// `stlc compile` (see [`calls::compile`]).
#[allow(unsafe_code)]
#[unsafe(no_mangle)]
pub extern "C" fn stlc_compile() -> u32 {
    run(calls::compile)
}

/// `stlc check` (see [`calls::check`]).
#[allow(unsafe_code)]
#[unsafe(no_mangle)]
pub extern "C" fn stlc_check() -> u32 {
    run(calls::check)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_leaves_its_message_as_a_failed_answer() {
        // An earlier answer is not left behind for the glue to read.
        OUTPUT.with(|o| *o.borrow_mut() = b"an earlier answer".to_vec());
        let unwound = std::panic::catch_unwind(|| run(|_| panic!("boom")));
        assert!(unwound.is_err());
        let out = OUTPUT.with(|o| o.borrow().clone());
        let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
        assert_eq!(v["ok"], false);
        let error = v["error"].as_str().unwrap();
        assert!(
            error.starts_with("the work stopped on a bug in stlc: panicked at")
                && error.ends_with("boom"),
            "{error}"
        );
    }
}

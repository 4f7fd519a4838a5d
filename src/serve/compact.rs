//! Big grown trees in the render answer: past [`BIG_TREE_STEMS`] stems the
//! tree is left out of the answer's SVG (which keeps the background and
//! the layout underneath) and out of its BED text, and the page draws it
//! on a canvas from the stems in growth order; and the compact body that
//! carries those stems as binary numbers instead of JSON text, for a
//! client that asks for it (`Accept: application/x-stlc-render`).
//!
//! The compact body, little-endian:
//!
//! | bytes | what |
//! | --- | --- |
//! | 4 | `n`: the length of the head, an unsigned integer |
//! | `n` | the head, JSON: `{"answer": A, "stems": k}`, padded with spaces so that `4 + n` is a multiple of 8 |
//! | `8 k` | `growth.stems`: `k` numbers (six a stem), IEEE 754 doubles |
//!
//! `A` is the render answer with `growth.stems` empty: put back, they give
//! the JSON answer, number for number.

use serde::Serialize;

use super::api::RenderAnswer;

/// A grown tree of more stems than this is drawn by the page from its
/// stems, not from the SVG: an SVG of 20,000 stems costs the page about
/// 60 ms to parse and draw, and its cost grows with the stems.
pub const BIG_TREE_STEMS: u64 = 20_000;

/// The media type of the compact body.
pub const MEDIA: &str = "application/x-stlc-render";

/// Whether an `Accept` header's value takes the compact body.
pub fn accepted(accept: Option<&str>) -> bool {
    accept.is_some_and(|a| {
        a.split(',')
            .any(|m| m.split(';').next().is_some_and(|t| t.trim() == MEDIA))
    })
}

/// The answer as a compact body (module docs).
pub fn body(mut answer: RenderAnswer) -> Result<Vec<u8>, serde_json::Error> {
    #[derive(Serialize)]
    struct Head<'a> {
        answer: &'a RenderAnswer,
        stems: usize,
    }
    let stems = std::mem::take(&mut answer.growth.stems);
    let mut head = serde_json::to_vec(&Head {
        answer: &answer,
        stems: stems.len(),
    })?;
    while !(4 + head.len()).is_multiple_of(8) {
        head.push(b' ');
    }
    let mut out = Vec::with_capacity(4 + head.len() + 8 * stems.len());
    // A head past 4 GiB cannot happen: the input is at most 4 GiB and the
    // head holds only its diagnostics and shapes.
    out.extend((head.len() as u32).to_le_bytes());
    out.extend(head);
    for x in &stems {
        out.extend(x.to_le_bytes());
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accept_headers_name_the_media_type_among_others() {
        assert!(accepted(Some(MEDIA)));
        assert!(accepted(Some(
            "application/json, application/x-stlc-render;q=0.9"
        )));
        assert!(!accepted(Some("application/json")));
        assert!(!accepted(Some("application/x-stlc-renderer")));
        assert!(!accepted(None));
    }
}

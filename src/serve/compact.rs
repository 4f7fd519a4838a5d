//! Big grown trees in the render answer: past [`BIG_TREE_STEMS`] stems (a
//! constant of `api.rs`, which the WebAssembly engine shares) the
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
//! | `n` | the head, JSON: `{"answer": A, "stems": k}`, padded with spaces so that `4 + n` is a multiple of 4 |
//! | `4 k` | `growth.stems`: `k` signed 32-bit integers, six a stem: coordinates and width in thousandths of a unit (the JSON answer's three decimals, exactly), then the decision |
//! | `4 m` | a 3D input's `space.stems` (`"space": m` in the head, absent for 2D): eight a stem, the same way (the decision last) |
//!
//! `A` is the render answer with `growth.stems` (and `space.stems`)
//! empty: put back (divided by 1000 but the decisions), they give the
//! JSON answer, number for number. Four bytes a number, about half what its JSON text takes; an
//! answer with a number out of their range (a coordinate past 2,147,483
//! units) goes as JSON.

use serde::Serialize;

pub use stlc::api::BIG_TREE_STEMS;
use stlc::api::RenderAnswer;

/// The media type of the compact body.
pub const MEDIA: &str = "application/x-stlc-render";

/// Whether an `Accept` header's value takes the compact body.
pub fn accepted(accept: Option<&str>) -> bool {
    accept.is_some_and(|a| {
        a.split(',')
            .any(|m| m.split(';').next().is_some_and(|t| t.trim() == MEDIA))
    })
}

/// The stems, `per` numbers a stem (the last the decision), as the
/// compact body's integers, if every one fits.
fn integers(stems: &[f64], per: usize) -> Option<Vec<i32>> {
    stems
        .iter()
        .enumerate()
        .map(|(i, &x)| {
            let v = if i % per == per - 1 {
                x
            } else {
                (x * 1000.0).round()
            };
            (v.is_finite() && v >= f64::from(i32::MIN) && v <= f64::from(i32::MAX))
                .then_some(v as i32)
        })
        .collect()
}

/// The answer as a compact body (module docs); `Err` with the answer
/// when a number does not fit.
pub fn body(mut answer: RenderAnswer) -> Result<Vec<u8>, Box<RenderAnswer>> {
    let Some(numbers) = integers(&answer.growth.stems, 6) else {
        return Err(Box::new(answer));
    };
    let space = answer.stems3.as_ref().map(|s| integers(&s.stems, 8));
    let space = match space {
        Some(None) => return Err(Box::new(answer)),
        Some(Some(n)) => Some(n),
        None => None,
    };
    #[derive(Serialize)]
    struct Head<'a> {
        answer: &'a RenderAnswer,
        stems: usize,
        #[serde(skip_serializing_if = "Option::is_none")]
        space: Option<usize>,
    }
    let stems = std::mem::take(&mut answer.growth.stems);
    let stems3_stems = answer.stems3.as_mut().map(|s| std::mem::take(&mut s.stems));
    let Ok(mut head) = serde_json::to_vec(&Head {
        answer: &answer,
        stems: stems.len(),
        space: space.as_ref().map(Vec::len),
    }) else {
        answer.growth.stems = stems;
        if let (Some(s), Some(kept)) = (answer.stems3.as_mut(), stems3_stems) {
            s.stems = kept;
        }
        return Err(Box::new(answer));
    };
    while !(4 + head.len()).is_multiple_of(4) {
        head.push(b' ');
    }
    let space = space.unwrap_or_default();
    let mut out = Vec::with_capacity(4 + head.len() + 4 * (numbers.len() + space.len()));
    // A head past 4 GiB cannot happen: the input is at most 4 GiB and the
    // head holds only its diagnostics and shapes.
    out.extend((head.len() as u32).to_le_bytes());
    out.extend(head);
    for x in numbers.into_iter().chain(space) {
        out.extend(x.to_le_bytes());
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_thousandths_but_decisions_and_too_far_is_none() {
        // Three-decimal numbers, as the answer rounds them.
        let stem = [323.253, -0.001, 2147483.647, 0.1, 0.5, 77.0];
        assert_eq!(
            integers(&stem, 6),
            Some(vec![323_253, -1, i32::MAX, 100, 500, 77])
        );
        assert_eq!(integers(&[2147483.648, 0.0, 0.0, 0.0, 0.0, 0.0], 6), None);
        assert_eq!(integers(&[f64::NAN, 0.0, 0.0, 0.0, 0.0, 0.0], 6), None);
        // Eight a stem in 3D: the eighth is the decision.
        let stem = [1.5, -2.0, 0.25, 0.0, 0.0, 0.001, 3.0, 9.0];
        assert_eq!(
            integers(&stem, 8),
            Some(vec![1500, -2000, 250, 0, 0, 1, 3000, 9])
        );
    }

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

//! How the editor spells the options a hint names ([`Page`]): its own
//! controls where it has them (the depth field, the max stems field), and
//! for what only a command line sets (the server's limits, the derivation
//! order) the command that sets it, so a browser user is never told to
//! "raise the limit with --max-stems N" as if the page took flags.

use crate::diag::{Bound, Knob, Spelling};

/// Which page reads the answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Page {
    /// The editor `stlc serve` serves: its limits are the server's flags.
    Served,
    /// The static web page: its limits are the command line's defaults.
    Web,
}

impl Page {
    /// Where a flag is given, for what the page has no control for.
    fn command_line(self, flag: &str, value: &str) -> String {
        let flag = match value {
            "" => flag.to_string(),
            v => format!("{flag} {v}"),
        };
        match self {
            Page::Served => format!("`stlc serve {flag}` (restart the server with it)"),
            Page::Web => {
                format!("`{flag}` of the stlc command line (the web page keeps the default limits)")
            }
        }
    }
}

impl Spelling for Page {
    fn knob(&self, knob: Knob, value: &str) -> String {
        match knob {
            Knob::Depth => "the depth field".into(),
            Knob::Seed => "the seed field".into(),
            Knob::Growth => "the growth order".into(),
            Knob::Clearance => "the clearance field".into(),
            Knob::Size => match value {
                "" => "the export size".into(),
                v => format!("the export size {v}"),
            },
            // Options only the command line has: the command that takes it.
            Knob::Exact | Knob::Sides | Knob::Triangles => match value {
                "" => format!("`stlc render {}`", knob.flag()),
                v => format!("`stlc render {} {v}`", knob.flag()),
            },
            Knob::Limit(Bound::Stems) => "the max stems field".into(),
            Knob::Derivation => {
                format!("`stlc render --derivation {value}` (the page derives depth-first)")
            }
            Knob::Limit(b) => self.command_line(b.flag(), value),
        }
    }

    fn raise(&self, bound: Bound) -> String {
        format!(
            "raise the limit with {}",
            self.command_line(bound.flag(), bound.value_name())
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diag::Help;

    #[test]
    fn the_page_names_its_controls_and_the_command_behind_a_limit() {
        let h = Help::from("the BED is valid but its tree is cut short; ") + Bound::Stems;
        assert_eq!(
            h.spell(&Page::Served),
            "the BED is valid but its tree is cut short; raise the limit with \
             `stlc serve --max-stems N` (restart the server with it)"
        );
        assert_eq!(
            h.spell(&Page::Web),
            "the BED is valid but its tree is cut short; raise the limit with \
             `--max-stems N` of the stlc command line (the web page keeps the default limits)"
        );
        // What only the command line sets is named as the command.
        let h = Help::from("drop ")
            + Help::knob(Knob::Exact, "")
            + ", use fewer "
            + Help::knob(Knob::Sides, "6");
        assert_eq!(h.flags(), "drop --exact, use fewer --sides 6");
        assert_eq!(
            h.spell(&Page::Web),
            "drop `stlc render --exact`, use fewer `stlc render --sides 6`"
        );
        let h = Help::from("ask for ") + Help::knob(Knob::Size, "800x800");
        assert_eq!(h.flags(), "ask for --size 800x800");
        assert_eq!(h.spell(&Page::Served), "ask for the export size 800x800");
        let h = Help::from("lower ") + Help::knob(Knob::Depth, "");
        assert_eq!(h.spell(&Page::Served), "lower the depth field");
        assert_eq!(h.flags(), "lower --depth");
    }
}

//! A diagnostic's hint ([`Help`]) with the options it names kept as data
//! ([`Knob`]): the library never spells an option, each front end does
//! ([`Spelling`]): the command line as a flag (`--max-stems N`, [`Flags`]),
//! the editor as its control or the server it runs on (`stlc::api`).

use std::ops::Add;

use super::Bound;

/// An option a hint names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Knob {
    /// The derivation depth of an `.lsys` (`--depth`).
    Depth,
    /// The seed of stochastic rules (`--seed`).
    Seed,
    /// The growth order of an `.od` (`--growth`).
    Growth,
    /// The derivation order (`--derivation`).
    Derivation,
    /// The clearance of growth (`--clearance`).
    Clearance,
    /// The picture's size (`--size`).
    Size,
    /// Every segment drawn, no level of detail (`--exact`).
    Exact,
    /// The sides of a mesh's tubes (`--sides`).
    Sides,
    /// The most triangles a mesh may hold (`--max-triangles`).
    Triangles,
    /// A limit (`--max-*`).
    Limit(Bound),
}

impl Knob {
    /// The command-line flag.
    pub fn flag(self) -> &'static str {
        match self {
            Knob::Depth => "--depth",
            Knob::Seed => "--seed",
            Knob::Growth => "--growth",
            Knob::Derivation => "--derivation",
            Knob::Clearance => "--clearance",
            Knob::Size => "--size",
            Knob::Exact => "--exact",
            Knob::Sides => "--sides",
            Knob::Triangles => "--max-triangles",
            Knob::Limit(b) => b.flag(),
        }
    }
}

/// A piece of a hint.
#[derive(Debug, Clone, PartialEq)]
pub enum Part {
    /// Words.
    Text(String),
    /// An option and the value it is shown with (`N`, `dfs`; empty for
    /// none).
    Knob(Knob, String),
    /// How to raise a limit (`raise the limit with --max-depth N`).
    Raise(Bound),
}

/// How a front end spells the options a hint names.
pub trait Spelling {
    /// `knob` shown with `value`.
    fn knob(&self, knob: Knob, value: &str) -> String;
    /// How to raise `bound`.
    fn raise(&self, bound: Bound) -> String;
}

/// The command line's spelling: flags.
#[derive(Debug, Clone, Copy, Default)]
pub struct Flags;

impl Spelling for Flags {
    fn knob(&self, knob: Knob, value: &str) -> String {
        match value {
            "" => knob.flag().to_string(),
            v => format!("{} {v}", knob.flag()),
        }
    }

    fn raise(&self, bound: Bound) -> String {
        format!(
            "raise the limit with {} {}",
            bound.flag(),
            bound.value_name()
        )
    }
}

/// How to fix a problem, in one sentence, with the options it names as
/// data.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Help(pub Vec<Part>);

impl Help {
    /// A hint that names `knob` shown with `value`.
    pub fn knob(knob: Knob, value: &str) -> Help {
        Help(vec![Part::Knob(knob, value.to_string())])
    }

    /// The hint as `spelling` writes it.
    pub fn spell(&self, spelling: &dyn Spelling) -> String {
        let mut out = String::new();
        for part in &self.0 {
            match part {
                Part::Text(t) => out.push_str(t),
                Part::Knob(k, v) => out.push_str(&spelling.knob(*k, v)),
                Part::Raise(b) => out.push_str(&spelling.raise(*b)),
            }
        }
        out
    }

    /// The hint as the command line writes it.
    pub fn flags(&self) -> String {
        self.spell(&Flags)
    }

    /// The options the hint names.
    pub fn knobs(&self) -> impl Iterator<Item = Knob> + '_ {
        self.0.iter().filter_map(|p| match p {
            Part::Knob(k, _) => Some(*k),
            Part::Raise(b) => Some(Knob::Limit(*b)),
            Part::Text(_) => None,
        })
    }
}

impl From<&str> for Help {
    fn from(t: &str) -> Help {
        Help(vec![Part::Text(t.to_string())])
    }
}

impl From<String> for Help {
    fn from(t: String) -> Help {
        Help(vec![Part::Text(t)])
    }
}

impl From<Bound> for Help {
    /// How to raise the limit.
    fn from(b: Bound) -> Help {
        Help(vec![Part::Raise(b)])
    }
}

impl<T: Into<Help>> Add<T> for Help {
    type Output = Help;
    fn add(mut self, rest: T) -> Help {
        self.0.extend(rest.into().0);
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A spelling that marks what it spells, to see each part land.
    struct Marks;
    impl Spelling for Marks {
        fn knob(&self, knob: Knob, value: &str) -> String {
            format!("<{knob:?} {value}>")
        }
        fn raise(&self, bound: Bound) -> String {
            format!("<raise {bound:?}>")
        }
    }

    #[test]
    fn a_hint_keeps_its_options_as_data_and_each_spelling_writes_them() {
        let h = Help::from("use a smaller depth, or ")
            + Bound::Depth
            + " ("
            + Help::knob(Knob::Limit(Bound::Word), "N")
            + " for bfs)";
        assert_eq!(
            h.flags(),
            "use a smaller depth, or raise the limit with --max-depth N (--max-word N for bfs)"
        );
        assert_eq!(
            h.spell(&Marks),
            "use a smaller depth, or <raise Depth> (<Limit(Word) N> for bfs)"
        );
        assert_eq!(
            h.knobs().collect::<Vec<_>>(),
            [Knob::Limit(Bound::Depth), Knob::Limit(Bound::Word)]
        );
        assert_eq!(Help::knob(Knob::Size, "").flags(), "--size");
    }
}

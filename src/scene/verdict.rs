//! What a claim or a step's `gives` is found to be, and what it is meant to be.

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    Agrees,
    Disagrees,
    NotCheckable,
    /// The symbolic test and the random-point test contradict each other: neither an
    /// agreement nor an erratum until someone looks.
    Undecided,
}

impl Verdict {
    pub fn as_str(self) -> &'static str {
        match self {
            Verdict::Agrees => "agrees",
            Verdict::Disagrees => "disagrees",
            Verdict::NotCheckable => "not-checkable",
            Verdict::Undecided => "undecided",
        }
    }
}

/// What a claim is: the notes' statement, whose disagreement is an erratum, or a common mistake
/// written down on purpose for students to spot, whose disagreement is the point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ClaimRole {
    #[default]
    Notes,
    Mistake,
}

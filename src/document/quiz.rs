//! A lecture's problems as questions for the learning-management systems that take one number
//! per blank (QTI 2.1, Canvas, Blackboard): one question per entry of each answer (a scalar, a
//! vector's component, a matrix's cell), each with every variant's statement, given values,
//! exact answer in f64 and tolerance. Moodle's cloze takes a variant's entries together and
//! reads the same labels and tolerances from here.

use super::course::{Documents, Lecture};
use super::problems::{Problem, Variant, answer_order, answer_words};
use crate::model::value::Value;

/// One entry of one answer of a problem, at every variant.
pub struct QuizPart<'a> {
    pub problem: &'a Problem,
    /// The answer's place among the problem's (0-based).
    pub answer: usize,
    /// The entry's place in the answer, and how it is named (`Some("row 1, column 2")`); a
    /// scalar's is `None`.
    pub entry: Option<(usize, String)>,
    /// The answer's words, with the entry's name: "Inertia tensor (row 1, column 2)".
    pub label: String,
    pub unit: Option<String>,
    /// The problem's agreement, relative to the answer's largest entry.
    pub relative: f64,
    pub variants: Vec<PartVariant<'a>>,
}

/// One variant of a quiz part.
pub struct PartVariant<'a> {
    pub variant: &'a Variant,
    /// The exact answer's entry in f64.
    pub answer: f64,
    /// The absolute tolerance: `relative` times the answer's largest entry at this variant.
    pub tolerance: f64,
}

impl QuizPart<'_> {
    /// A name for the part within its lecture: the problem's id, the answer's number and the
    /// entry's (`problem-pendulum-2`, `problem-box-1-5`), an XML name.
    pub fn id(&self) -> String {
        match &self.entry {
            None => format!("{}-{}", self.problem.id, self.answer + 1),
            Some((k, _)) => format!("{}-{}-{}", self.problem.id, self.answer + 1, k + 1),
        }
    }

    /// Whether a relative tolerance of the entry itself is the problem's agreement at every
    /// variant: a scalar answer, or an entry that is the largest of its answer everywhere.
    pub fn relative_is_exact(&self) -> bool {
        self.variants
            .iter()
            .all(|v| v.answer != 0.0 && v.tolerance == self.relative * v.answer.abs())
    }
}

/// Each lecture's quiz parts, in the course's order: the lecture and the parts of its
/// problems, in the order of its pages. A lecture without a problem with variants has none.
pub fn lecture_quizzes<'a>(docs: &'a Documents) -> Vec<(&'a Lecture, Vec<QuizPart<'a>>)> {
    let mut out = Vec::new();
    for lecture in &docs.lectures {
        let parts: Vec<QuizPart> = lecture
            .pages
            .iter()
            .filter_map(|i| docs.problems.iter().find(|(j, _)| j == i))
            .flat_map(|(_, p)| quiz_parts(p))
            .collect();
        if !parts.is_empty() {
            out.push((lecture, parts));
        }
    }
    out
}

/// The name of the `k`-th (0-based) of the files a long lecture's export is split into:
/// `lecture-1.txt`, then `lecture-1-2.txt`, ….
pub fn split_file(slug: &str, k: usize, extension: &str) -> String {
    if k == 0 {
        format!("{slug}.{extension}")
    } else {
        format!("{slug}-{}.{extension}", k + 1)
    }
}

/// A problem's quiz parts: each entry of each answer.
pub fn quiz_parts(problem: &Problem) -> Vec<QuizPart<'_>> {
    let Some(first) = problem.variants.first() else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for (k, spec) in problem.answers.iter().enumerate() {
        let entries = entry_names(&first.answers[k].exact);
        for (e, name) in entries.iter().enumerate() {
            let label = answer_label(spec);
            out.push(QuizPart {
                problem,
                answer: k,
                entry: name.clone().map(|n| (e, n)),
                label: match name {
                    Some(n) => format!("{label}, {n}"),
                    None => label,
                },
                unit: spec.unit.as_ref().map(|u| u.text.clone()),
                relative: spec.tolerance,
                variants: problem
                    .variants
                    .iter()
                    .map(|v| {
                        let numbers = &v.answers[k].exact_numbers;
                        PartVariant {
                            variant: v,
                            answer: numbers[e],
                            tolerance: tolerance(spec.tolerance, numbers),
                        }
                    })
                    .collect(),
            });
        }
    }
    out
}

/// The name of each entry of a value, in the order of its numbers: none for a scalar,
/// "component 2" of a vector, "row 1, column 2" of a matrix.
fn entry_names(v: &Value) -> Vec<Option<String>> {
    match v {
        Value::Scalar(_) => vec![None],
        Value::Vector(_) => (1..=3).map(|k| Some(format!("component {k}"))).collect(),
        Value::Matrix(_) => (0..9)
            .map(|k| Some(format!("row {}, column {}", k / 3 + 1, k % 3 + 1)))
            .collect(),
    }
}

/// An answer's absolute tolerance: `relative` to its largest entry, so that a zero entry is not
/// asked for exactly.
pub fn tolerance(relative: f64, numbers: &[f64]) -> f64 {
    let scale = numbers.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    relative * scale
}

/// An answer's words, as on the key, with the order its entries take when it has several:
/// "Principal moments (in ascending order, I1 ≤ I2 ≤ I3)". An expression without a label is
/// shown as written; a label may hold the author's `$…$`.
pub fn answer_label(spec: &crate::scene::Answer) -> String {
    if let Some(words) = &spec.label {
        return crate::base::format::capitalised(words);
    }
    let Some(name) = spec.bare_quantity() else {
        return spec.written.clone();
    };
    let words = answer_words(name);
    match answer_order(name) {
        Some(order) => format!("{words} ({order})"),
        None => words.to_string(),
    }
}

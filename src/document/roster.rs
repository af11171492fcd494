//! Which sheet variant each student of a roster gets: a seeded shuffle of the sheet's
//! variants, dealt to the students in the roster's order, so the same roster and seed give the
//! same papers. A variant goes to one student at most.

use super::Sheet;
use crate::base::rng::Rng;
use crate::scene::roster::Roster;

/// A lecture's sheet has fewer variants than the roster has students.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "{}: {students} students, but lecture {lecture}'s problem sheet has {}: \
     a variant goes to one student, so give its problem scenes `count = {students}` or more in \
     [variants] (or use a shorter roster)",
    roster.display(),
    crate::base::format::count(.variants, "variant")
)]
pub struct TooFewVariants {
    pub roster: std::path::PathBuf,
    pub lecture: String,
    pub students: usize,
    pub variants: usize,
}

/// For each student, in the roster's order, the index of their sheet variant.
pub fn assign(
    roster: &Roster,
    sheet: &Sheet,
    lecture: &str,
    seed: u64,
) -> Result<Vec<usize>, TooFewVariants> {
    let n = sheet.variants.len();
    if roster.students.len() > n {
        return Err(TooFewVariants {
            roster: roster.source.clone(),
            lecture: lecture.to_string(),
            students: roster.students.len(),
            variants: n,
        });
    }
    // Fisher-Yates with the seeded stream.
    let mut order: Vec<usize> = (0..n).collect();
    let mut rng = Rng::new(seed);
    for i in (1..n).rev() {
        let j = ((rng.uniform() * (i + 1) as f64) as usize).min(i);
        order.swap(i, j);
    }
    order.truncate(roster.students.len());
    Ok(order)
}

//! The time a scene's numeric checks may take together. Each check is bounded on its own (its
//! steps, its points, its tolerance); this bounds their sum, so that a scene of many slow steps
//! or variants stops with a located message instead of running for hours.

use std::time::{Duration, Instant};

/// A course's scenes check in milliseconds to a few seconds; the slowest shipped one in 2.6 s.
pub const CHECKS_TIME_BUDGET: Duration = Duration::from_secs(120);

/// When a scene's numeric checks started, and how long they may take.
#[derive(Debug, Clone, Copy)]
pub struct Deadline {
    start: Instant,
    budget: Duration,
}

impl Deadline {
    /// The budget of [`CHECKS_TIME_BUDGET`], from now.
    pub fn checks() -> Deadline {
        Deadline::after(CHECKS_TIME_BUDGET)
    }

    pub fn after(budget: Duration) -> Deadline {
        Deadline {
            start: Instant::now(),
            budget,
        }
    }

    /// Why the next check may not start, once the budget is spent.
    pub fn check(&self) -> Result<(), OverBudget> {
        let spent = self.start.elapsed();
        if spent >= self.budget {
            return Err(OverBudget {
                seconds: spent.as_secs_f64(),
                budget: self.budget.as_secs(),
            });
        }
        Ok(())
    }
}

#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error(
    "not checked: the scene's numeric checks before this one took {seconds:.0} s, past the \
     {budget} s they may take together; split the scene, or give its problem fewer variants"
)]
pub struct OverBudget {
    pub seconds: f64,
    pub budget: u64,
}

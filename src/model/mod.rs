//! The shared vocabulary every stage reads: the catalogue of outputs, stages and quantities;
//! the exact value of a quantity and its evaluation at the scene's values; fidelity; validated
//! principal moments; and the figure data type.

pub mod catalogue;
pub mod fidelity;
pub mod figure;
pub mod moments;
pub mod prose;
pub mod units;
pub mod value;

//! The bottom layer: neutral utilities that know nothing of mechanics or of any stage.

pub mod float;
pub mod format;
pub mod hash;
pub mod in_order;
pub mod literal;
pub mod markup;
pub mod natural;
pub mod pencil;
pub mod rng;
pub mod suggest;
pub mod zip;

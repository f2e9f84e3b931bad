//! Joint sections: placeholder, filled in below.
use super::{Frame, Page};
use crate::plan::Plan;

/// One page per kind of joint.
pub fn pages(_plan: &Plan, _frame: &Frame) -> Vec<Page> {
    Vec::new()
}

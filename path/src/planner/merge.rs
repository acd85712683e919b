//! HMC's merge rules beyond the buffer modes (digest 000 §3.4, §6.7; manual §4.4.7.6, §10.6):
//! the speed-ripple suppression ratio (`HMC_SetMergeSpeedTolerRatio`) and "merge is invalid
//! when even deep look-ahead cannot reach the normal merge speed" (§10.6 (8): the next
//! command is a tiny move such as `HMC_MoveEx(1)`: the path decelerates normally, to rest).
//! Off unless set ([`PathPlanner::set_merge_rule`]): NMC, HIMC and PLCopen blending pass a
//! junction as fast as the look-ahead allows, however much below the buffer mode's velocity.

use super::{PathPlanner, PlannerError};

/// Relative margin under which a reachable junction velocity still counts as the requested
/// one (rounding of the look-ahead's square roots).
const REACH_MARGIN: f64 = 1e-9;

/// HMC's merge rules for a planner's blended junctions without corner geometry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MergeRule {
    /// HMC_SetMergeSpeedTolerRatio, [0, 1] (default 0): a corner-angle factor `k` of at least
    /// `1 − speed_tolerance` counts as 1, so small corners (a curve drawn in short lines from
    /// coarse points) no longer make the junction velocity ripple. Larger suppresses more and
    /// lets the path pass more corners faster ("may increase impact", manual §4.4.7.6); the
    /// axes' own limits still hold.
    pub speed_tolerance: f64,
}

impl MergeRule {
    /// HMC's default: no ripple suppression.
    pub const HMC_DEFAULT: MergeRule = MergeRule {
        speed_tolerance: 0.0,
    };

    /// The corner-angle factor `k` after the ripple suppression.
    pub fn suppress(&self, k: f64) -> f64 {
        if k >= 1.0 - self.speed_tolerance {
            1.0
        } else {
            k
        }
    }
}

/// The preferred velocity at a blended junction under HMC's rule: `requested` (the buffer
/// mode's velocity within the junction's caps) if the motions after it can take it
/// (`reachable`, the look-ahead's start velocity of the next motion), else 0 — an exact stop
/// (§10.6 (8)). Without the rule, the lower of the two.
pub(super) fn junction_preference(rule: Option<MergeRule>, requested: f64, reachable: f64) -> f64 {
    match rule {
        Some(_) if reachable < requested * (1.0 - REACH_MARGIN) => 0.0,
        _ => requested.min(reachable),
    }
}

impl PathPlanner {
    /// HMC's merge rules (see [`MergeRule`]); `None` (the default) turns them off. They apply
    /// to motions pushed from now on (the ripple suppression) and to the look-ahead from its
    /// next pass (the exact stop). Refused unless `0 ≤ speed_tolerance ≤ 1`.
    pub fn set_merge_rule(&mut self, rule: Option<MergeRule>) -> Result<(), PlannerError> {
        if let Some(r) = rule {
            if !(0.0..=1.0).contains(&r.speed_tolerance) {
                return Err(PlannerError::Invalid(
                    "the merge speed tolerance ratio is 0 to 1",
                ));
            }
        }
        self.merge_rule = rule;
        Ok(())
    }

    pub fn merge_rule(&self) -> Option<MergeRule> {
        self.merge_rule
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tolerance_flattens_small_dips_only() {
        let r = MergeRule {
            speed_tolerance: 0.3,
        };
        assert_eq!(r.suppress(0.75), 1.0);
        assert_eq!(r.suppress(0.5), 0.5);
        assert_eq!(MergeRule::HMC_DEFAULT.suppress(0.99), 0.99);
        assert_eq!(MergeRule::HMC_DEFAULT.suppress(1.0), 1.0);
    }

    #[test]
    fn an_unreachable_merge_velocity_is_an_exact_stop() {
        let hmc = Some(MergeRule::HMC_DEFAULT);
        assert_eq!(junction_preference(hmc, 50.0, 44.7), 0.0);
        assert_eq!(junction_preference(hmc, 50.0, 60.0), 50.0);
        assert_eq!(junction_preference(None, 50.0, 44.7), 44.7);
    }
}

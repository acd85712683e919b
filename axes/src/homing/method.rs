//! The CiA 402 method table: one row per method, read by the one machine in `machine.rs`.

use super::{HomingError, HomingHardware, HomingInput};
use crate::types::Direction;

/// A direction of travel with arithmetic.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Dir {
    Pos,
    Neg,
}

impl Dir {
    pub(super) fn sign(self) -> f64 {
        match self {
            Dir::Pos => 1.0,
            Dir::Neg => -1.0,
        }
    }

    pub(super) fn reverse(self) -> Dir {
        match self {
            Dir::Pos => Dir::Neg,
            Dir::Neg => Dir::Pos,
        }
    }

    /// Direction of travel from `from` to `to` (positive when equal).
    pub(super) fn towards(from: f64, to: f64) -> Dir {
        if to < from {
            Dir::Neg
        } else {
            Dir::Pos
        }
    }

    pub(super) fn public(self) -> Direction {
        match self {
            Dir::Pos => Direction::Positive,
            Dir::Neg => Direction::Negative,
        }
    }
}

/// The input whose edge defines the home point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Signal {
    Home,
    LimitNeg,
    LimitPos,
}

impl Signal {
    pub(super) fn input(self) -> HomingInput {
        match self {
            Signal::Home => HomingInput::HomeSwitch,
            Signal::LimitNeg => HomingInput::NegativeLimit,
            Signal::LimitPos => HomingInput::PositiveLimit,
        }
    }
}

/// Where the signal is active along the axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Shape {
    /// Active above one edge: CiA 402 "positive home switch", the positive limit.
    Above,
    /// Active below one edge: "negative home switch", the negative limit.
    Below,
    /// Active between two edges: the home cam of methods 7–14, 23–30.
    Cam,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Edge {
    Lower,
    Upper,
}

/// Position relative to the signal's active region. The order is the axis order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum Region {
    Left,
    Inside,
    Right,
}

impl Region {
    /// The region outside the signal on side `d`.
    pub(super) fn outside(d: Dir) -> Region {
        match d {
            Dir::Pos => Region::Right,
            Dir::Neg => Region::Left,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct SwitchMethod {
    pub signal: Signal,
    pub shape: Shape,
    pub edge: Edge,
    /// The limit that reverses the search (methods 7–14, 23–30).
    pub reversal: Option<Dir>,
}

impl SwitchMethod {
    /// The region from which moving in `approach` crosses the home edge.
    pub(super) fn ready_region(&self, approach: Dir) -> Region {
        match (self.edge, approach) {
            (Edge::Lower, Dir::Pos) => Region::Left,
            (Edge::Upper, Dir::Neg) => Region::Right,
            (Edge::Lower, Dir::Neg) | (Edge::Upper, Dir::Pos) => Region::Inside,
        }
    }

    /// Region when the signal is inactive and nothing else is known; `None` outside a cam.
    pub(super) fn inactive_region(&self) -> Option<Region> {
        match self.shape {
            Shape::Above => Some(Region::Left),
            Shape::Below => Some(Region::Right),
            Shape::Cam => None,
        }
    }

    /// The direction searched when the signal is inactive (towards the switch, or towards the
    /// reversal limit for a cam).
    pub(super) fn nominal(&self) -> Dir {
        match (self.shape, self.reversal) {
            (Shape::Above, _) => Dir::Pos,
            (Shape::Below, _) => Dir::Neg,
            (Shape::Cam, Some(d)) => d,
            (Shape::Cam, None) => Dir::Pos,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    Switch(SwitchMethod),
    /// 33, 34: the next index pulse in the approach direction.
    IndexOnly,
    /// 35, 37: the current position.
    Current,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct MethodDef {
    pub kind: Kind,
    /// Direction in which the home edge is crossed and the index searched ("A").
    pub approach: Dir,
    /// The home point is the first index pulse after the edge.
    pub index: bool,
}

impl MethodDef {
    /// The method's row, or `UnsupportedMethod` (15, 16, 31, 32, 36, anything outside 1–37).
    pub(super) fn lookup(method: i16) -> Result<MethodDef, HomingError> {
        use Dir::{Neg, Pos};
        use Edge::{Lower, Upper};
        use Shape::{Above, Below, Cam};
        use Signal::{Home, LimitNeg, LimitPos};
        let unsupported = HomingError::UnsupportedMethod { method };
        let (base, index) = match method {
            1..=14 => (method, true),
            17..=30 => (method - 16, false),
            33 | 34 => {
                let approach = if method == 33 { Neg } else { Pos };
                return Ok(MethodDef {
                    kind: Kind::IndexOnly,
                    approach,
                    index: true,
                });
            }
            35 | 37 => {
                return Ok(MethodDef {
                    kind: Kind::Current,
                    approach: Pos,
                    index: false,
                })
            }
            _ => return Err(unsupported),
        };
        // (signal, shape, home edge, approach, reversal limit): the CiA 402 diagrams. "Index
        // left of the edge" is an approach in the negative direction.
        let (signal, shape, edge, approach, reversal) = match base {
            1 => (LimitNeg, Below, Upper, Pos, None),
            2 => (LimitPos, Above, Lower, Neg, None),
            3 => (Home, Above, Lower, Neg, None),
            4 => (Home, Above, Lower, Pos, None),
            5 => (Home, Below, Upper, Pos, None),
            6 => (Home, Below, Upper, Neg, None),
            7 => (Home, Cam, Lower, Neg, Some(Pos)),
            8 => (Home, Cam, Lower, Pos, Some(Pos)),
            9 => (Home, Cam, Upper, Neg, Some(Pos)),
            10 => (Home, Cam, Upper, Pos, Some(Pos)),
            11 => (Home, Cam, Upper, Pos, Some(Neg)),
            12 => (Home, Cam, Upper, Neg, Some(Neg)),
            13 => (Home, Cam, Lower, Pos, Some(Neg)),
            14 => (Home, Cam, Lower, Neg, Some(Neg)),
            _ => return Err(unsupported),
        };
        Ok(MethodDef {
            kind: Kind::Switch(SwitchMethod {
                signal,
                shape,
                edge,
                reversal,
            }),
            approach,
            index,
        })
    }

    /// The inputs the method needs, in the order they are reported when missing.
    pub(super) fn required(&self) -> impl Iterator<Item = HomingInput> {
        let (signal, reversal) = match self.kind {
            Kind::Switch(s) => (Some(s.signal.input()), s.reversal),
            Kind::IndexOnly | Kind::Current => (None, None),
        };
        let reversal = reversal.map(|d| match d {
            Dir::Pos => HomingInput::PositiveLimit,
            Dir::Neg => HomingInput::NegativeLimit,
        });
        let index = (self.index && self.kind != Kind::Current).then_some(HomingInput::Index);
        signal.into_iter().chain(reversal).chain(index)
    }

    pub(super) fn check_hardware(
        &self,
        method: i16,
        hw: HomingHardware,
    ) -> Result<(), HomingError> {
        for input in self.required() {
            let present = match input {
                HomingInput::NegativeLimit => hw.limit_neg,
                HomingInput::PositiveLimit => hw.limit_pos,
                HomingInput::HomeSwitch => hw.home,
                HomingInput::Index => hw.index,
            };
            if !present {
                return Err(HomingError::MissingInput { method, input });
            }
        }
        Ok(())
    }

    /// Direction of the first search when the reference signal is inactive; the initial
    /// back-off goes the other way.
    pub(super) fn nominal(&self) -> Dir {
        match self.kind {
            Kind::Switch(s) => s.nominal(),
            Kind::IndexOnly | Kind::Current => self.approach,
        }
    }
}

//! The path length of the group motions a coordinate system pushes (`NMC_CrdGetBufLength`,
//! digest 001 §2.7), measured on the path crate's geometry, the same the engine's planner
//! runs: lines, arcs (centre, radius, three points, about a normal, with turns) and ellipses.

use axes::command::{ArcDirection, CircleMode, Command, GroupCommand};
use path::geometry::{Arc, Curve, Line, Segment, Turn};
use path::{Point, MAX_AXES};

fn point(v: &[f64]) -> Point {
    let mut p = [0.0; MAX_AXES];
    for (o, x) in p.iter_mut().zip(v) {
        *o = *x;
    }
    p
}

fn turn(d: ArcDirection) -> Turn {
    match d {
        ArcDirection::Ccw => Turn::Ccw,
        ArcDirection::Cw => Turn::Cw,
    }
}

/// The segment `command` moves along from `start` (engine units, the group's coordinates), and
/// where it ends; `None` for a command that does not move the path or a geometry the engine
/// would refuse (it is then not counted).
fn segment(start: &[f64], command: &Command) -> Option<(Segment, Vec<f64>)> {
    let dims = start.len().min(MAX_AXES);
    let s = point(start);
    let Command::Group(g) = command else {
        return None;
    };
    let built = match g {
        GroupCommand::MoveLinearAbsolute(c) => {
            Line::new(s, point(&c.position), dims).map(Segment::Line)
        }
        GroupCommand::MoveCircularAbsolute(c) => {
            let (aux, end) = (point(&c.aux_point), point(&c.end_point));
            let plane = c.plane.map_or((0, 1), |[i, j]| (i, j));
            match (c.mode, c.normal.as_deref()) {
                (CircleMode::Center, Some([x, y, z])) => Arc::from_center_normal(
                    s,
                    end,
                    aux,
                    [*x, *y, *z],
                    turn(c.direction),
                    c.turns,
                    [0, 1, 2],
                    dims,
                )
                .map(Segment::Arc),
                (CircleMode::Center, _) => {
                    Arc::from_center(s, end, aux, plane, turn(c.direction), c.turns, dims)
                        .map(Segment::Arc)
                }
                (CircleMode::Radius, _) => Arc::from_radius(
                    s,
                    end,
                    c.radius.unwrap_or(0.0),
                    plane,
                    turn(c.direction),
                    dims,
                )
                .map(Segment::Arc),
                (CircleMode::Border, _) => Segment::through_points(s, aux, end, dims),
            }
        }
        GroupCommand::MoveEllipse(c) => {
            let center = point(&c.center);
            let center = if c.relative {
                let mut o = s;
                for (a, b) in o.iter_mut().zip(&center) {
                    *a += b;
                }
                o
            } else {
                center
            };
            let plane = c.plane.map_or((0, 1), |[i, j]| (i, j));
            Curve::ellipse(s, center, c.ratio, plane, turn(c.direction), dims)
        }
        _ => return None,
    };
    let segment = built.ok()?;
    let end = segment.end();
    Some((segment, end.iter().take(dims).copied().collect()))
}

/// The total length of the motions among `commands`, in engine units, from `start`.
pub fn total(start: &[f64], commands: &[Command]) -> f64 {
    let mut at = start.to_vec();
    let mut length = 0.0;
    for c in commands {
        if let Some((segment, end)) = segment(&at, c) {
            length += segment.length();
            at = end;
        }
    }
    length
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use axes::command::{MoveCircularAbsolute, MoveLinearAbsolute};

    #[test]
    fn a_line_then_a_full_circle() {
        let line: Command = MoveLinearAbsolute {
            group: 0,
            position: vec![3.0, 4.0],
            velocity: None,
            acceleration: None,
            deceleration: None,
            jerk: None,
            buffer_mode: Default::default(),
            transition: Default::default(),
            user_segment: None,
            independent: Default::default(),
            coordinate_system: None,
        }
        .into();
        let circle: Command = MoveCircularAbsolute {
            group: 0,
            mode: CircleMode::Center,
            aux_point: vec![4.0, 4.0],
            radius: None,
            end_point: vec![3.0, 4.0],
            direction: ArcDirection::Ccw,
            plane: None,
            normal: None,
            turns: 0,
            velocity: None,
            acceleration: None,
            deceleration: None,
            jerk: None,
            buffer_mode: Default::default(),
            transition: Default::default(),
            user_segment: None,
            independent: Default::default(),
            coordinate_system: None,
        }
        .into();
        let l = total(&[0.0, 0.0], &[line, circle]);
        assert!((l - (5.0 + std::f64::consts::TAU)).abs() < 1e-9, "{l}");
    }
}

//! Coordinate systems: full circles through three points (digest 001 §2.7
//! `NMC_CrdCircle3DEx`, `NMC_CrdCirclePPP`), as one engine arc about the circle's centre from
//! the start back to it: about the normal of the three points' plane in 3-D, in XY for PPP.

use axes::command::{ArcDirection, CircleMode, Command, MoveCircularAbsolute, TransitionMode};
use mcemu_nmc::crd::CRD_MAX_AXES;
use mcemu_nmc::table::{self, Function};

use super::crd_segment::{at, read_longs, read_tail, user_segment, Push, Tail};
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::CRD_CIRCLE_3D_EX, crd_circle_3d_ex),
    (table::CRD_CIRCLE_PPP, crd_circle_ppp),
];

type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The centre of the circle through `p0`, `p1`, `p2` and the normal of their plane oriented so
/// that p0 → p1 → p2 turns counter-clockwise about it; `None` if they are on one line (or
/// coincide): no circle passes through them.
fn circumcircle(p0: V3, p1: V3, p2: V3) -> Option<(V3, V3)> {
    let (a, b) = (sub(p1, p0), sub(p2, p0));
    let n = cross(a, b);
    let nn = dot(n, n);
    let scale = dot(a, a).max(dot(b, b));
    // Collinear within a part in 10¹² of the points' spread (or not finite): no circle.
    if nn.is_nan() || nn <= 1e-12 * scale * scale {
        return None;
    }
    let w = cross(
        [
            dot(a, a) * b[0] - dot(b, b) * a[0],
            dot(a, a) * b[1] - dot(b, b) * a[1],
            dot(a, a) * b[2] - dot(b, b) * a[2],
        ],
        n,
    );
    let center = [
        p0[0] + w[0] / (2.0 * nn),
        p0[1] + w[1] / (2.0 * nn),
        p0[2] + w[2] / (2.0 * nn),
    ];
    Some((center, n))
}

fn no_circle() -> Refusal {
    Refusal::range(
        "pMidPos/pTgPos",
        "points on one line",
        "three points that fix a circle",
    )
}

/// The full circle from the path's end (`start`, user coordinates in pulses) about `center`
/// (pulses, the coordinates past the plane the start's), in `plane` or about `normal`.
#[allow(clippy::too_many_arguments)]
fn circle(
    p: &Push,
    seg_no: i64,
    start: &[i64; CRD_MAX_AXES],
    center: &[f64],
    plane: Option<[usize; 2]>,
    normal: Option<V3>,
    direction: ArcDirection,
    t: &Tail,
) -> Command {
    let (velocity, acc, buffer_mode) = p.kinematics(t);
    let aux_point = p
        .scales
        .iter()
        .enumerate()
        .map(|(k, s)| {
            s.to_engine(
                center
                    .get(k)
                    .copied()
                    .unwrap_or(start.get(k).copied().unwrap_or(0) as f64),
            )
        })
        .collect();
    MoveCircularAbsolute {
        group: p.group(),
        mode: CircleMode::Center,
        aux_point,
        radius: None,
        end_point: p.engine(start),
        direction,
        plane,
        normal: normal.map(|n| n.to_vec()),
        turns: 0,
        velocity: Some(velocity),
        acceleration: Some(acc),
        deceleration: Some(acc),
        jerk: Some(0.0),
        buffer_mode,
        transition: TransitionMode::None,
        user_segment: user_segment(seg_no),
        independent: Default::default(),
        coordinate_system: None,
    }
    .into()
}

/// A full 3-D circle from the path's end through `pMidPos` and `pTgPos` (XYZ) back to the start.
fn crd_circle_3d_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let seg_no = c.input.i64()?;
    let (mid, target) = (read_longs(c)?, read_longs(c)?);
    let t = read_tail(c, true)?;
    p.need(3, "a 3-D circle")?;
    let start = p.s.end;
    let xyz = |v: &[i64], name: &str| -> Result<V3, Refusal> {
        Ok([
            at(v, 0, name)? as f64,
            at(v, 1, name)? as f64,
            at(v, 2, name)? as f64,
        ])
    };
    let s3 = [start[0] as f64, start[1] as f64, start[2] as f64];
    let (center, normal) =
        circumcircle(s3, xyz(&mid, "pMidPos")?, xyz(&target, "pTgPos")?).ok_or_else(no_circle)?;
    let command = circle(
        &p,
        seg_no,
        &start,
        &center,
        None,
        Some(normal),
        ArcDirection::Ccw,
        &t,
    );
    p.finish(c, vec![command], start)
}

/// The full XY circle through `pStPos`, `pMidPosArray` and `pTgPosArray`, from and back to
/// `pStPos` (a line to it first where the path is elsewhere); planeIdx 0 only ("only XY
/// supported", digest 001 §2.7).
fn crd_circle_ppp(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let seg_no = c.input.i64()?;
    let plane = c.input.i16()?;
    let (st, mid, target) = (read_longs(c)?, read_longs(c)?, read_longs(c)?);
    let t = read_tail(c, true)?;
    if plane != 0 {
        return Err(Refusal::range(
            "planeIdx",
            plane,
            "{0 (XY)}: the manual supports only XY",
        ));
    }
    p.need(2, "an XY circle")?;
    let xy = |v: &[i64], name: &str| -> Result<V3, Refusal> {
        Ok([at(v, 0, name)? as f64, at(v, 1, name)? as f64, 0.0])
    };
    let s3 = xy(&st, "pStPos")?;
    let (center, normal) = circumcircle(s3, xy(&mid, "pMidPosArray")?, xy(&target, "pTgPosArray")?)
        .ok_or_else(no_circle)?;
    let mut start = p.s.end;
    start[0] = at(&st, 0, "pStPos")?;
    start[1] = at(&st, 1, "pStPos")?;
    let mut commands: Vec<Command> = p.line(seg_no, &start, &t).into_iter().collect();
    let direction = if normal[2] > 0.0 {
        ArcDirection::Ccw
    } else {
        ArcDirection::Cw
    };
    commands.push(circle(
        &p,
        seg_no,
        &start,
        &center[..2],
        Some([0, 1]),
        None,
        direction,
        &t,
    ));
    p.finish(c, commands, start)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_circle_through_three_points() {
        let Some((c, n)) = circumcircle([0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [2.0, 0.0, 0.0]) else {
            panic!("no circle");
        };
        assert!((c[0] - 1.0).abs() < 1e-12 && c[1].abs() < 1e-12 && c[2].abs() < 1e-12);
        // 0 → (1,1) → (2,0) turns clockwise in XY: the normal points down.
        assert!(n[2] < 0.0);
        assert!(circumcircle([0.0; 3], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0]).is_none());
    }
}

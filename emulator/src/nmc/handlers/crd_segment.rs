//! Coordinate systems: the buffered segments (lines, arcs, helix, ellipse) and buffered
//! commands (DO, delay, wait, axis moves) of digest 001 §2.7, as engine group commands. Before
//! `NMC_CrdStartMtn` they wait in the service (`CrdState::pending`), after it they go to the
//! engine at once. Positions are pulses in user coordinates; a coordinate a segment does not
//! name keeps the value the previous segment ends with (`CrdState::end`).

use axes::command::{
    ArcDirection, CircleMode, Command, GroupAxisMove, GroupBufferMode, GroupDwell, GroupId,
    GroupSetOutput, GroupWaitInput, GroupWaitPosition, MoveCircularAbsolute, MoveEllipse,
    MoveLinearAbsolute, TransitionMode,
};
use mcemu_dialects::nmc::{acceleration_to_engine, velocity_to_engine};
use mcemu_dialects::PulseScale;
use mcemu_nmc::crd::{LineD8Unit, CRD_MAX_AXES, D8_PACK_MAX};
use mcemu_nmc::table::{self, Function};

use super::crd::{crd, here, members, state, update};
use super::sync_args::{axes_of_mask, axis_number};
use crate::nmc::crd::{CrdState, CRD_BUFFER};
use crate::nmc::service::{pulses, Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::CRD_LINE_XYZ_EX, crd_line_xyz_ex),
    (table::CRD_LINE_XYZA, crd_line_xyza),
    (table::CRD_LINE_XYZ, crd_line_xyz),
    (table::CRD_LINE_XYZ_D8, crd_line_xyz_d8),
    (table::CRD_LINE_XYZ_D8_PACK, crd_line_xyz_d8_pack),
    (table::CRD_ARC_CENTER_EX, crd_arc_center_ex),
    (table::CRD_ARC_CENTER_YZ_EX, crd_arc_center_yz_ex),
    (table::CRD_ARC_CENTER_ZX_EX, crd_arc_center_zx_ex),
    (table::CRD_ARC_CENTER, crd_arc_center),
    (table::CRD_ARC_RADIUS_EX, crd_arc_radius_ex),
    (table::CRD_ARC_RADIUS_YZ_EX, crd_arc_radius_yz_ex),
    (table::CRD_ARC_RADIUS_ZX_EX, crd_arc_radius_zx_ex),
    (table::CRD_ARC_PPP_EX, crd_arc_ppp_ex),
    (table::CRD_HELIX_CENTER_EX, crd_helix_center_ex),
    (table::CRD_ARC_3D_EX, crd_arc_3d_ex),
    (table::CRD_ARC_3D, crd_arc_3d),
    (table::CRD_ELLIPSE, crd_ellipse),
    (table::CRD_BUF_DO, crd_buf_do),
    (table::CRD_BUF_DO_EX, crd_buf_do_ex),
    (table::CRD_BUF_DELAY, crd_buf_delay),
    (table::CRD_BUF_WAIT_DI, crd_buf_wait_di),
    (table::CRD_BUF_AX_MOVE_EX, crd_buf_ax_move_ex),
    (
        table::CRD_BUF_WAIT_ENC_IN_POSITION,
        crd_buf_wait_enc_in_position,
    ),
    (table::CRD_BUF_SET_PTP_MOVE_PARA, crd_buf_set_ptp_move_para),
    (table::CRD_BUF_AX_MOVE_REL, crd_buf_ax_move_rel),
];

const XY: [usize; 2] = [0, 1];
const YZ: [usize; 2] = [1, 2];
const ZX: [usize; 2] = [2, 0];

/// endVel, vel, synAcc and lookaheadDis (0 for the legacy forms): every segment's tail.
#[derive(Clone, Copy, Debug)]
pub(super) struct Tail {
    end_vel: f64,
    vel: f64,
    syn_acc: f64,
    lookahead_dis: i16,
}

pub(super) fn read_tail(c: &mut Call<'_>, with_lookahead: bool) -> Result<Tail, Refusal> {
    let t = Tail {
        end_vel: c.input.f64()?,
        vel: c.input.f64()?,
        syn_acc: c.input.f64()?,
        lookahead_dis: if with_lookahead { c.input.i16()? } else { 0 },
    };
    check_tail(&t)?;
    Ok(t)
}

fn check_tail(t: &Tail) -> Result<(), Refusal> {
    if !(t.end_vel.is_finite() && t.end_vel >= 0.0) {
        return Err(Refusal::range("endVel", t.end_vel, "[0, ∞) pulse/ms"));
    }
    if !(t.vel.is_finite() && t.vel > 0.0) {
        return Err(Refusal::range("vel", t.vel, "(0, ∞) pulse/ms"));
    }
    if !(t.syn_acc.is_finite() && t.syn_acc > 0.0) {
        return Err(Refusal::range("synAcc", t.syn_acc, "(0, ∞) pulse/ms²"));
    }
    if !(0..=1).contains(&t.lookahead_dis) {
        return Err(Refusal::range("lookaheadDis", t.lookahead_dis, "{0, 1}"));
    }
    Ok(())
}

/// An array argument: u16 count, then i64s (at most 64: no manual array is longer).
pub(super) fn read_longs(c: &mut Call<'_>) -> Result<Vec<i64>, Refusal> {
    let n = usize::from(c.input.u16()?);
    if n > 64 {
        return Err(Refusal::range("array length", n, "[0, 64]"));
    }
    (0..n)
        .map(|_| c.input.i64().map_err(Refusal::from))
        .collect()
}

/// `a[k]`, or a refusal naming the short array.
pub(super) fn at(a: &[i64], k: usize, name: &str) -> Result<i64, Refusal> {
    a.get(k)
        .copied()
        .ok_or_else(|| Refusal::range(name, format!("{} values", a.len()), "the manual's length"))
}

/// The user segment number the engine reports (`NMC_CrdGetUserSegNo`): negative ones read 0.
pub(super) fn user_segment(seg_no: i64) -> Option<u32> {
    Some(u32::try_from(seg_no).unwrap_or(0))
}

/// One coordinate system's segment being built: its members and their scales.
pub(super) struct Push {
    pub(super) n: usize,
    pub(super) s: CrdState,
    pub(super) axes: Vec<usize>,
    pub(super) scales: Vec<PulseScale>,
    /// Where the path stands before this push (user coordinates, pulses).
    start: [i64; CRD_MAX_AXES],
}

impl Push {
    pub(super) fn begin(c: &mut Call<'_>) -> Result<Push, Refusal> {
        let n = crd(c)?;
        let mut s = state(c, n);
        let axes = members(&s)?;
        if !s.started && s.pending.is_empty() {
            // At rest with nothing pushed: the path starts where the axes are now.
            s.end = here(c, n, &s);
            s.ext_end.clear();
        }
        let scales = axes.iter().map(|a| c.scale(*a)).collect();
        let start = s.end;
        Ok(Push {
            n,
            s,
            axes,
            scales,
            start,
        })
    }

    pub(super) fn group(&self) -> GroupId {
        self.n as GroupId
    }

    /// Path units: the first member's (decisions.md).
    pub(super) fn path_scale(&self) -> PulseScale {
        self.scales.first().copied().unwrap_or(PulseScale {
            pulses_per_unit: 1.0,
        })
    }

    fn dims(&self) -> usize {
        self.axes.len().min(CRD_MAX_AXES)
    }

    /// The user coordinates `p` (pulses) in engine units, one per member.
    pub(super) fn engine(&self, p: &[i64; CRD_MAX_AXES]) -> Vec<f64> {
        self.scales
            .iter()
            .zip(p)
            .map(|(s, v)| s.to_engine(*v as f64))
            .collect()
    }

    /// The coordinate system must have `needed` coordinates for `what`.
    pub(super) fn need(&self, needed: usize, what: &str) -> Result<(), Refusal> {
        if self.dims() >= needed {
            Ok(())
        } else {
            Err(Refusal::new(
                mcemu_dialects::nmc::code_for_kind(axes::command::ErrorKind::InvalidGroup),
                format!(
                    "{what} needs {needed} coordinates; the coordinate system has {}",
                    self.dims()
                ),
            ))
        }
    }

    /// Velocity, acceleration and buffer mode of a segment: `vel` and `synAcc` within
    /// synVelMax/synAccMax and the safety limits; blended unless look-ahead is off or the
    /// segment asks to end at rest (lookaheadDis 1, endVel 0).
    pub(super) fn kinematics(&self, t: &Tail) -> (f64, f64, GroupBufferMode) {
        let v = t.vel.min(self.s.para.syn_vel_max).min(self.s.safe.max_vel);
        let a = t
            .syn_acc
            .min(self.s.para.syn_acc_max)
            .min(self.s.safe.max_acc);
        let exact = self.s.ext.look_ahead_switch == 0 || (t.lookahead_dis == 1 && t.end_vel == 0.0);
        let mode = if exact {
            GroupBufferMode::Buffered
        } else {
            GroupBufferMode::BlendingLow
        };
        let scale = self.path_scale();
        (
            velocity_to_engine(scale, v),
            acceleration_to_engine(scale, a),
            mode,
        )
    }

    pub(super) fn line(
        &self,
        seg_no: i64,
        target: &[i64; CRD_MAX_AXES],
        t: &Tail,
    ) -> Option<Command> {
        if *target == self.s.end {
            // No displacement: nothing for the path to do (the engine refuses empty lines).
            return None;
        }
        let (velocity, acc, buffer_mode) = self.kinematics(t);
        Some(
            MoveLinearAbsolute {
                group: self.group(),
                position: self.engine(target),
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
            .into(),
        )
    }

    #[allow(clippy::too_many_arguments)]
    fn arc(
        &self,
        seg_no: i64,
        mode: CircleMode,
        aux: &[i64; CRD_MAX_AXES],
        radius: Option<f64>,
        end: &[i64; CRD_MAX_AXES],
        direction: ArcDirection,
        plane: Option<[usize; 2]>,
        turns: u32,
        t: &Tail,
    ) -> Command {
        let (velocity, acc, buffer_mode) = self.kinematics(t);
        MoveCircularAbsolute {
            group: self.group(),
            mode,
            aux_point: if mode == CircleMode::Radius {
                Vec::new()
            } else {
                self.engine(aux)
            },
            radius: radius.map(|r| self.path_scale().to_engine(r)),
            end_point: self.engine(end),
            direction,
            plane,
            normal: None,
            turns,
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

    /// Queue `commands` (pending before the start, to the engine after it) and remember where
    /// the path ends (and, with `NMC_CrdSetBufLengthFlag` 1, how long it is).
    pub(super) fn finish(
        mut self,
        c: &mut Call<'_>,
        commands: Vec<Command>,
        end: [i64; CRD_MAX_AXES],
    ) -> Result<(), Refusal> {
        if self.s.length_flag {
            let start = self.engine(&self.start);
            let length = crate::nmc::crd_length::total(&start, &commands);
            self.s.pushed_length += self.path_scale().from_engine(length);
        }
        if self.s.started {
            if let Some(polar) = super::crd::polar_resume(c, self.n) {
                c.command(polar);
            }
            c.plan.commands.extend(commands);
        } else {
            if self.s.pending.len() + commands.len() > CRD_BUFFER {
                return Err(Refusal::new(
                    mcemu_dialects::nmc::code_for_kind(axes::command::ErrorKind::QueueFull),
                    format!("the buffer holds {CRD_BUFFER} commands (BIT_CORD_FULL)"),
                ));
            }
            self.s.pending.extend(commands);
        }
        self.s.end = end;
        self.s.pushed += 1;
        let (n, s) = (self.n, self.s);
        update(c, n, |now| *now = s);
        Ok(())
    }

    /// Where an axis outside the coordinate system ends after what was pushed.
    pub(super) fn ext_end(&self, c: &Call<'_>, axis: usize) -> i64 {
        self.s
            .ext_end
            .iter()
            .find(|(a, _)| *a == axis)
            .map(|(_, p)| *p)
            .unwrap_or_else(|| {
                c.status(axis)
                    .map_or(0, |st| pulses(c.scale(axis), st.cmd_pos))
            })
    }

    pub(super) fn set_ext_end(&mut self, axis: usize, p: i64) {
        self.s.ext_end.retain(|(a, _)| *a != axis);
        self.s.ext_end.push((axis, p));
    }

    /// An axis outside the coordinate system (by number), checked.
    pub(super) fn outside(&self, c: &Call<'_>, axis: usize, name: &str) -> Result<(), Refusal> {
        if axis >= c.snapshot.axes.len() || self.axes.contains(&axis) {
            return Err(Refusal::range(
                name,
                format!("axis {axis}"),
                "an axis of the device outside the coordinate system",
            ));
        }
        Ok(())
    }
}

fn direction(dir: i16) -> Result<ArcDirection, Refusal> {
    match dir {
        0 => Ok(ArcDirection::Cw),
        1 => Ok(ArcDirection::Ccw),
        d => Err(Refusal::range("circleDir", d, "{0 (CW), 1 (CCW)}")),
    }
}

/// A line to the coordinates of `mask` (bit k = coordinate k; `pTgPosArray[k]` its target).
fn line(c: &mut Call<'_>, dims: usize, with_lookahead: bool) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let seg_no = c.input.i64()?;
    let mask = c.input.i16()?;
    let target = read_longs(c)?;
    let t = read_tail(c, with_lookahead)?;
    let mut end = p.s.end;
    for (k, e) in end.iter_mut().enumerate().take(dims) {
        if mask & (1 << k) != 0 {
            if k >= p.dims() {
                return Err(Refusal::range(
                    "crdAxMask",
                    format!("{mask:#x}"),
                    &format!("bits 0 … {} (the coordinate system's axes)", p.dims() - 1),
                ));
            }
            *e = at(&target, k, "pTgPosArray")?;
        }
    }
    if mask < 0 || (mask as u16) >> dims != 0 {
        return Err(Refusal::range(
            "crdAxMask",
            format!("{mask:#x}"),
            &format!("bits 0 … {}", dims - 1),
        ));
    }
    let commands = p.line(seg_no, &end, &t).into_iter().collect();
    p.finish(c, commands, end)
}

fn crd_line_xyz_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    line(c, 3, true)
}

fn crd_line_xyza(c: &mut Call<'_>) -> Result<(), Refusal> {
    line(c, 4, true)
}

/// The examples' legacy form: lookaheadDis 0.
fn crd_line_xyz(c: &mut Call<'_>) -> Result<(), Refusal> {
    line(c, 3, false)
}

/// Up to 8 axes: the coordinates of `crdAxMask`, then the axes of `extAxMask` by number
/// (outside the coordinate system), their targets in that order (digest 001 §2.7). The extra
/// axes run buffered single-axis moves that start with the line, at the speed that ends them
/// with it when the line runs at `vel` (their own ramps make them a little later).
fn d8(
    c: &mut Call<'_>,
    p: &mut Push,
    u: &LineD8Unit,
    crd_mask: i64,
    ext_mask: i64,
    t: &Tail,
) -> Result<(Vec<Command>, [i64; CRD_MAX_AXES]), Refusal> {
    if crd_mask < 0 || crd_mask >> p.dims() != 0 {
        return Err(Refusal::range(
            "crdAxmask",
            format!("{crd_mask:#x}"),
            &format!("bits 0 … {} (the coordinate system's axes)", p.dims() - 1),
        ));
    }
    let ext_axes = axes_of_mask(c, "extAxMask", ext_mask, 32)?;
    let mut values = u.tg_pos.iter().copied();
    let mut end = p.s.end;
    for (k, e) in end.iter_mut().enumerate().take(p.dims()) {
        if crd_mask & (1 << k) != 0 {
            *e = values.next().unwrap_or(0);
        }
    }
    let mut ext = Vec::new();
    for axis in ext_axes {
        p.outside(c, axis, "extAxMask")?;
        let target = values
            .next()
            .ok_or_else(|| Refusal::range("pTgPosArray", "more than 8 axes", "8 values"))?;
        ext.push((axis, target));
    }
    let length =
        p.s.end
            .iter()
            .zip(&end)
            .map(|(a, b)| ((b - a) as f64).powi(2))
            .sum::<f64>()
            .sqrt();
    let longest = ext
        .iter()
        .map(|(a, target)| (target - p.ext_end(c, *a)).abs() as f64)
        .fold(0.0, f64::max);
    let vel = t.vel.min(p.s.para.syn_vel_max).min(p.s.safe.max_vel);
    let acc = t.syn_acc.min(p.s.para.syn_acc_max).min(p.s.safe.max_acc);
    let duration_ms = if length > 0.0 {
        length / vel
    } else {
        longest / vel
    };
    let mut commands = Vec::new();
    for (axis, target) in ext {
        let distance = (target - p.ext_end(c, axis)).abs() as f64;
        if distance > 0.0 && duration_ms > 0.0 {
            let scale = c.scale(axis);
            commands.push(
                GroupAxisMove {
                    group: p.group(),
                    axis: axis as u16,
                    position: scale.to_engine(target as f64),
                    velocity: Some(velocity_to_engine(scale, distance / duration_ms)),
                    acceleration: Some(acceleration_to_engine(scale, acc)),
                    deceleration: Some(acceleration_to_engine(scale, acc)),
                    jerk: None,
                }
                .into(),
            );
        }
        p.set_ext_end(axis, target);
    }
    commands.extend(p.line(u.seg_no, &end, t));
    Ok((commands, end))
}

fn crd_line_xyz_d8(c: &mut Call<'_>) -> Result<(), Refusal> {
    let mut p = Push::begin(c)?;
    let seg_no = c.input.i64()?;
    let (crd_mask, ext_mask) = (c.input.i64()?, c.input.i64()?);
    let target = read_longs(c)?;
    let t = read_tail(c, true)?;
    let mut u = LineD8Unit {
        seg_no,
        ..LineD8Unit::default()
    };
    for (k, v) in u.tg_pos.iter_mut().enumerate() {
        *v = at(&target, k, "pTgPosArray")?;
    }
    let (commands, end) = d8(c, &mut p, &u, crd_mask, ext_mask, &t)?;
    p.finish(c, commands, end)
}

/// `count` ∈ [1, 18] (TV53); each unit as one `NMC_CrdLineXYZD8`, all or none.
fn crd_line_xyz_d8_pack(c: &mut Call<'_>) -> Result<(), Refusal> {
    let mut p = Push::begin(c)?;
    let count = c.input.i16()?;
    let n = usize::from(c.input.u16()?);
    if !(1..=D8_PACK_MAX as i16).contains(&count) || n != count as usize {
        return Err(Refusal::range("count", count, "[1, 18] (TV53)"));
    }
    let units = (0..n)
        .map(|_| LineD8Unit::read(&mut c.input).map_err(Refusal::from))
        .collect::<Result<Vec<_>, _>>()?;
    let mut commands = Vec::new();
    for u in &units {
        let t = Tail {
            end_vel: u.end_vel,
            vel: u.vel,
            syn_acc: u.acc,
            lookahead_dis: u.lookahead_dis,
        };
        check_tail(&t)?;
        let (more, end) = d8(
            c,
            &mut p,
            u,
            i64::from(u.crd_ax_mask),
            i64::from(u.ext_ax_mask),
            &t,
        )?;
        commands.extend(more);
        p.s.end = end;
        p.s.pushed += 1;
    }
    let end = p.s.end;
    p.s.pushed = p.s.pushed.saturating_sub(1);
    p.finish(c, commands, end)
}

/// An arc in `plane` by its end and its centre relative to the start (digest 001 §4.4: the
/// centre is always an offset from the start point); end = start is a full circle.
fn arc_center(c: &mut Call<'_>, plane: [usize; 2], with_lookahead: bool) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let seg_no = c.input.i64()?;
    let (target, center) = (read_longs(c)?, read_longs(c)?);
    let dir = direction(c.input.i16()?)?;
    let t = read_tail(c, with_lookahead)?;
    p.need(plane[0].max(plane[1]) + 1, "this arc's plane")?;
    let (mut end, mut aux) = (p.s.end, p.s.end);
    for (i, k) in plane.into_iter().enumerate() {
        end[k] = at(&target, i, "pTgPosArray")?;
        aux[k] = p.s.end[k].saturating_add(at(&center, i, "pCenterPosArray")?);
    }
    let arc = p.arc(
        seg_no,
        CircleMode::Center,
        &aux,
        None,
        &end,
        dir,
        Some(plane),
        0,
        &t,
    );
    p.finish(c, vec![arc], end)
}

fn crd_arc_center_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    arc_center(c, XY, true)
}

fn crd_arc_center_yz_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    arc_center(c, YZ, true)
}

fn crd_arc_center_zx_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    arc_center(c, ZX, true)
}

/// The examples' legacy XY form: lookaheadDis 0.
fn crd_arc_center(c: &mut Call<'_>) -> Result<(), Refusal> {
    arc_center(c, XY, false)
}

/// radius > 0 the minor arc, < 0 the major arc (TV45).
fn arc_radius(c: &mut Call<'_>, plane: [usize; 2]) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let seg_no = c.input.i64()?;
    let target = read_longs(c)?;
    let radius = c.input.f64()?;
    let dir = direction(c.input.i16()?)?;
    let t = read_tail(c, true)?;
    if !(radius.is_finite() && radius != 0.0) {
        return Err(Refusal::range("radius", radius, "a non-zero pulse count"));
    }
    p.need(plane[0].max(plane[1]) + 1, "this arc's plane")?;
    let mut end = p.s.end;
    for (i, k) in plane.into_iter().enumerate() {
        end[k] = at(&target, i, "pTgPosArray")?;
    }
    let arc = p.arc(
        seg_no,
        CircleMode::Radius,
        &end,
        Some(radius),
        &end,
        dir,
        Some(plane),
        0,
        &t,
    );
    p.finish(c, vec![arc], end)
}

fn crd_arc_radius_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    arc_radius(c, XY)
}

fn crd_arc_radius_yz_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    arc_radius(c, YZ)
}

fn crd_arc_radius_zx_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    arc_radius(c, ZX)
}

/// An arc from the start through `mid` to the end, in the first `dims` coordinates.
fn through(c: &mut Call<'_>, dims: usize, with_lookahead: bool) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let seg_no = c.input.i64()?;
    let (mid, target) = (read_longs(c)?, read_longs(c)?);
    let t = read_tail(c, with_lookahead)?;
    p.need(dims, "this arc")?;
    let (mut end, mut aux) = (p.s.end, p.s.end);
    for k in 0..dims {
        aux[k] = at(&mid, k, "pMidPos")?;
        end[k] = at(&target, k, "pTgPos")?;
    }
    let arc = p.arc(
        seg_no,
        CircleMode::Border,
        &aux,
        None,
        &end,
        ArcDirection::Ccw,
        None,
        0,
        &t,
    );
    p.finish(c, vec![arc], end)
}

fn crd_arc_ppp_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    through(c, 2, true)
}

fn crd_arc_3d_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    through(c, 3, true)
}

/// The examples' legacy form: lookaheadDis 0 (S-CRD-3DARC).
fn crd_arc_3d(c: &mut Call<'_>) -> Result<(), Refusal> {
    through(c, 3, false)
}

/// An XY circle about the centre (relative to the start) with Z linear: `rounds` whole turns
/// (TV46; a fraction is refused, decisions.md).
fn crd_helix_center_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let seg_no = c.input.i64()?;
    let (target, center) = (read_longs(c)?, read_longs(c)?);
    let dir = direction(c.input.i16()?)?;
    let rounds = c.input.f64()?;
    let t = read_tail(c, true)?;
    if !(rounds.is_finite() && (0.0..=10_000.0).contains(&rounds) && rounds.fract() == 0.0) {
        return Err(Refusal::range(
            "rounds",
            rounds,
            "a whole number in [0, 10000]",
        ));
    }
    p.need(3, "a helix")?;
    let (mut end, mut aux) = (p.s.end, p.s.end);
    for (k, e) in end.iter_mut().enumerate().take(3) {
        *e = at(&target, k, "pTgPosArray")?;
    }
    for k in XY {
        aux[k] = p.s.end[k].saturating_add(at(&center, k, "pCenterPosArray")?);
    }
    let turns = rounds as u32;
    let arc = p.arc(
        seg_no,
        CircleMode::Center,
        &aux,
        None,
        &end,
        dir,
        Some(XY),
        turns,
        &t,
    );
    p.finish(c, vec![arc], end)
}

/// The full XY ellipse about the centre (relative to the start); abRatio [0.05, 1]; at rest at
/// both ends, no look-ahead (digest 001 §4.4).
fn crd_ellipse(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let seg_no = c.input.i64()?;
    let ratio = c.input.f64()?;
    let center = read_longs(c)?;
    let dir = c.input.i16()?;
    let t = Tail {
        end_vel: 0.0,
        vel: c.input.f64()?,
        syn_acc: c.input.f64()?,
        lookahead_dis: 1,
    };
    check_tail(&t)?;
    if !(0.05..=1.0).contains(&ratio) {
        return Err(Refusal::range("abRatio", ratio, "[0.05, 1]"));
    }
    let direction = match dir {
        0 => ArcDirection::Cw,
        1 => ArcDirection::Ccw,
        d => return Err(Refusal::range("ellipseDir", d, "{0 (CW), 1 (CCW)}")),
    };
    p.need(2, "an ellipse")?;
    let mut rel = [0i64; CRD_MAX_AXES];
    for k in XY {
        rel[k] = at(&center, k, "pCenterPos")?;
    }
    let (velocity, acc, _) = p.kinematics(&t);
    let command = MoveEllipse {
        group: p.group(),
        center: p
            .scales
            .iter()
            .zip(rel)
            .map(|(s, v)| s.to_engine(v as f64))
            .collect(),
        ratio,
        direction,
        plane: Some(XY),
        relative: true,
        velocity: Some(velocity),
        acceleration: Some(acc),
        deceleration: Some(acc),
        jerk: Some(0.0),
        buffer_mode: GroupBufferMode::Buffered,
        transition: TransitionMode::None,
        user_segment: user_segment(seg_no),
        coordinate_system: None,
    }
    .into();
    let end = p.s.end;
    p.finish(c, vec![command], end)
}

/// A buffered command that does not move the path.
pub(super) fn marker(c: &mut Call<'_>, p: Push, commands: Vec<Command>) -> Result<(), Refusal> {
    let end = p.s.end;
    p.finish(c, commands, end)
}

/// The output channel of `doType` bit `ch` (digest 001 §3.10): GPDO1 bits 0–31, GPDO2 32–63,
/// extension module k 64 + 32·(k − 1) …; the motor enable/clear outputs are not buffered
/// outputs in mcemu (refused).
pub(super) fn do_channel(c: &Call<'_>, do_type: i16, ch: i64) -> Result<u16, Refusal> {
    if !(0..32).contains(&ch) {
        return Err(Refusal::range("ch", ch, "[0, 31]"));
    }
    let base = match do_type {
        3 => 0,
        4 => 32,
        5..=10 => 64 + 32 * (i64::from(do_type) - 5),
        1 | 2 => {
            return Err(Refusal::new(
                mcemu_nmc::errors::RTN_UNSUPPORTED,
                format!(
                    "doType {do_type}: buffered servo-enable/alarm-clear outputs are not modelled"
                ),
            ))
        }
        t => return Err(Refusal::range("doType", t, "[1, 10] (CRD_BUFF_DO_*)")),
    };
    let channel = base + ch;
    let count = c.snapshot.io.do_.len();
    usize::try_from(channel)
        .ok()
        .filter(|ch| *ch < count)
        .map(|ch| ch as u16)
        .ok_or_else(|| Refusal::range("ch", channel, &format!("the device's {count} outputs")))
}

fn crd_buf_do(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let (do_type, ch, value) = (c.input.i16()?, c.input.i64()?, c.input.i64()?);
    let channel = do_channel(c, do_type, ch)?;
    if !(0..=1).contains(&value) {
        return Err(Refusal::range("value", value, "{0, 1}"));
    }
    let command = GroupSetOutput {
        group: p.group(),
        channel,
        value: value == 1,
    };
    marker(c, p, vec![command.into()])
}

/// The bits of `doMask` in group `group` (bits group·32 …) set to `doValue`'s.
fn crd_buf_do_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let (group, mask, value) = (c.input.i16()?, c.input.i64()?, c.input.i64()?);
    let count = c.snapshot.io.do_.len();
    let groups = count.div_ceil(32);
    let start = usize::try_from(group)
        .ok()
        .filter(|g| *g < groups)
        .map(|g| g * 32)
        .ok_or_else(|| {
            Refusal::range(
                "group",
                group,
                &format!("[0, {}]", groups.saturating_sub(1)),
            )
        })?;
    let commands = (0..32)
        .filter(|i| mask & (1 << i) != 0 && start + i < count)
        .map(|i| {
            GroupSetOutput {
                group: p.group(),
                channel: (start + i) as u16,
                value: value & (1 << i) != 0,
            }
            .into()
        })
        .collect();
    marker(c, p, commands)
}

/// scale 0: ms, 1: s (TV54).
fn crd_buf_delay(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let (scale, count) = (c.input.i16()?, c.input.i64()?);
    let unit = match scale {
        0 => 1e-3,
        1 => 1.0,
        s => return Err(Refusal::range("scale", s, "{0 (ms), 1 (s)}")),
    };
    if count < 0 {
        return Err(Refusal::range("count", count, "[0, ∞)"));
    }
    let command = GroupDwell {
        group: p.group(),
        seconds: count as f64 * unit,
    };
    marker(c, p, vec![command.into()])
}

/// index [0, 127] (a DI of the device), diValue 0/1, waitLastTime ms (0: no limit; past it the
/// coordinate system stops with MVERR, decisions.md).
fn crd_buf_wait_di(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let (index, level, time) = (c.input.i16()?, c.input.i16()?, c.input.i64()?);
    let count = c.snapshot.io.di.len().min(128);
    let channel = usize::try_from(index)
        .ok()
        .filter(|i| *i < count)
        .ok_or_else(|| {
            Refusal::range("index", index, &format!("[0, {}]", count.saturating_sub(1)))
        })?;
    if !(0..=1).contains(&level) {
        return Err(Refusal::range("diValue", level, "{0, 1}"));
    }
    if time < 0 {
        return Err(Refusal::range("waitLastTime", time, "[0, ∞) ms"));
    }
    let command = GroupWaitInput {
        group: p.group(),
        channel: channel as u16,
        level: level == 1,
        timeout: (time > 0).then_some(time as f64 / 1e3),
    };
    marker(c, p, vec![command.into()])
}

/// The buffered moves of the axes of `mask` (by number, outside the coordinate system) to
/// `target(axis, value)` of their values in mask order; blockEn (without synEn) makes the
/// path wait until they arrive.
#[allow(clippy::too_many_arguments)]
fn axis_moves(
    c: &Call<'_>,
    p: &mut Push,
    mask: i16,
    values: &[i64],
    kinematics: impl Fn(usize) -> Result<(f64, f64), Refusal>,
    target: impl Fn(&Push, usize, i64) -> i64,
    block: i16,
    syn: i16,
) -> Result<Vec<Command>, Refusal> {
    if !(0..=1).contains(&block) {
        return Err(Refusal::range("blockEn", block, "{0, 1}"));
    }
    if !(0..=1).contains(&syn) {
        return Err(Refusal::range("synEn", syn, "{0, 1}"));
    }
    let mut moves = Vec::new();
    let mut waits = Vec::new();
    let mut given = values.iter().copied();
    // A `short` mask: the local axes only (the bus drives start at bit 16).
    for axis in axes_of_mask(c, "axisMask", i64::from(mask as u16), 16)? {
        p.outside(c, axis, "axisMask")?;
        let value = given
            .next()
            .ok_or_else(|| Refusal::range("positions", values.len(), "one value per mask bit"))?;
        let to = target(p, axis, value);
        let (vel, acc) = kinematics(axis)?;
        let scale = c.scale(axis);
        moves.push(
            GroupAxisMove {
                group: p.group(),
                axis: axis as u16,
                position: scale.to_engine(to as f64),
                velocity: Some(velocity_to_engine(scale, vel)),
                acceleration: Some(acceleration_to_engine(scale, acc)),
                deceleration: Some(acceleration_to_engine(scale, acc)),
                jerk: None,
            }
            .into(),
        );
        if block == 1 && syn == 0 {
            waits.push(
                GroupWaitPosition {
                    group: p.group(),
                    axis: axis as u16,
                    position: scale.to_engine(to as f64),
                    tolerance: None,
                    timeout: None,
                    condition: Default::default(),
                    source: Default::default(),
                }
                .into(),
            );
        }
        p.set_ext_end(axis, to);
    }
    moves.extend(waits);
    Ok(moves)
}

/// Absolute moves of axes outside the coordinate system (mask by axis number, one target per
/// bit) that start when the path reaches them.
fn crd_buf_ax_move_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    let mut p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let mask = c.input.i16()?;
    let targets = read_longs(c)?;
    let (vel, acc) = (c.input.f64()?, c.input.f64()?);
    let (block, syn) = (c.input.i16()?, c.input.i16()?);
    if !(vel.is_finite() && vel > 0.0) {
        return Err(Refusal::range("vel", vel, "(0, ∞) pulse/ms"));
    }
    if !(acc.is_finite() && acc > 0.0) {
        return Err(Refusal::range("acc", acc, "(0, ∞) pulse/ms²"));
    }
    let moves = axis_moves(
        c,
        &mut p,
        mask,
        &targets,
        |_| Ok((vel, acc)),
        |_, _, v| v,
        block,
        syn,
    )?;
    marker(c, p, moves)
}

/// Relative moves of axes outside the coordinate system, from where the pushed commands leave
/// them, with `NMC_CrdBufSetPtpMovePara`'s velocity and acceleration (synEn too: the engine
/// cannot take the next segment's timing, decisions.md).
fn crd_buf_ax_move_rel(c: &mut Call<'_>) -> Result<(), Refusal> {
    let mut p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let mask = c.input.i16()?;
    let distances = read_longs(c)?;
    let (block, syn) = (c.input.i16()?, c.input.i16()?);
    let para = p.s.axis_ptp.clone();
    let kinematics = |axis: usize| {
        para.iter()
            .find(|(a, _, _)| *a == axis)
            .map(|(_, v, a)| (*v, *a))
            .ok_or_else(|| {
                Refusal::new(
                    mcemu_dialects::nmc::code_for_kind(axes::command::ErrorKind::InvalidState),
                    format!("axis {axis}: NMC_CrdBufSetPtpMovePara first (its velocity and acceleration)"),
                )
            })
    };
    let target = |p: &Push, axis: usize, d: i64| p.ext_end(c, axis).saturating_add(d);
    let moves = axis_moves(c, &mut p, mask, &distances, kinematics, target, block, syn)?;
    marker(c, p, moves)
}

/// The velocity and acceleration of later relative axis moves of `axisNo`; smoothCoef
/// [0, 199] ms is checked and not used (the engine's buffered axis move has no smoothing).
fn crd_buf_set_ptp_move_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let mut p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let axis = c.input.i16()?;
    let (vel, acc, smooth) = (c.input.f64()?, c.input.f64()?, c.input.i16()?);
    let axis = axis_number(c, "axisNo", i64::from(axis))?;
    p.outside(c, axis, "axisNo")?;
    if !(vel.is_finite() && vel > 0.0) {
        return Err(Refusal::range("vel", vel, "(0, ∞) pulse/ms"));
    }
    if !(acc.is_finite() && acc > 0.0) {
        return Err(Refusal::range("acc", acc, "(0, ∞) pulse/ms²"));
    }
    if !(0..=199).contains(&smooth) {
        return Err(Refusal::range("soomthCoef", smooth, "[0, 199] ms"));
    }
    p.s.axis_ptp.retain(|(a, _, _)| *a != axis);
    p.s.axis_ptp.push((axis, vel, acc));
    marker(c, p, Vec::new())
}

/// Wait until the axes of `axisMask` (by number) are in position where the pushed commands
/// leave them (their `in_position_window`); overTime ms (0: no limit; past it MVERR).
fn crd_buf_wait_enc_in_position(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let (mask, time) = (c.input.i64()?, c.input.i64()?);
    let masked = axes_of_mask(c, "axisMask", mask, 32)?;
    if time < 0 {
        return Err(Refusal::range("overTime", time, "[0, ∞) ms"));
    }
    let origin = p.s.origin();
    let mut waits = Vec::new();
    for axis in masked {
        let at = match p.axes.iter().position(|m| *m == axis) {
            Some(k) => {
                p.s.end
                    .get(k)
                    .copied()
                    .unwrap_or(0)
                    .saturating_add(origin.get(k).copied().unwrap_or(0))
            }
            None => p.ext_end(c, axis),
        };
        waits.push(
            GroupWaitPosition {
                group: p.group(),
                axis: axis as u16,
                position: c.scale(axis).to_engine(at as f64),
                tolerance: None,
                timeout: (time > 0).then_some(time as f64 / 1e3),
                condition: Default::default(),
                source: Default::default(),
            }
            .into(),
        );
    }
    marker(c, p, waits)
}

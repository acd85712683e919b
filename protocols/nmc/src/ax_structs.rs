//! The structs of the axis-level additions (digest 001 §3.4, §3.6, §3.17: packed status, packed
//! PTP moves, the advanced E-stop input, the closed loop's DAC and PID) as the wire carries them, with the rules of
//! `crate::structs`: fields in declaration order, `long` as i64, `float` as f64, `reserved`
//! members not sent. Fixed-size arrays go element by element, no count.

use crate::payload::{PayloadError, Reader, Writer};

/// Axes in one `TMovePtpPack8`.
pub const PACK8_AXES: usize = 8;
/// Axes in one `TAxisStsPack12Ex`.
pub const PACK12_AXES: usize = 12;
/// Advanced E-stop input groups (`ESTOP_DI_EX_CH_NUM`: named, never given a value by the
/// manual, digest 001 §8; mcemu's choice, docs/decisions.md).
pub const ESTOP_DI_EX_CH_NUM: usize = 4;

fn put_f64s(w: &mut Writer, v: &[f64]) {
    for x in v {
        w.f64(*x);
    }
}

fn get_f64s<const N: usize>(r: &mut Reader<'_>) -> Result<[f64; N], PayloadError> {
    let mut out = [0.0; N];
    for x in &mut out {
        *x = r.f64()?;
    }
    Ok(out)
}

fn put_i16s(w: &mut Writer, v: &[i16]) {
    for x in v {
        w.i16(*x);
    }
}

fn get_i16s<const N: usize>(r: &mut Reader<'_>) -> Result<[i16; N], PayloadError> {
    let mut out = [0; N];
    for x in &mut out {
        *x = r.i16()?;
    }
    Ok(out)
}

fn put_i64s(w: &mut Writer, v: &[i64]) {
    for x in v {
        w.i64(*x);
    }
}

fn get_i64s<const N: usize>(r: &mut Reader<'_>) -> Result<[i64; N], PayloadError> {
    let mut out = [0; N];
    for x in &mut out {
        *x = r.i64()?;
    }
    Ok(out)
}

/// `TMovePtpPack8` (digest 001 §3.6): up to 8 consecutive axes from the first handle's, bit i
/// of `axis_mask` for axis first + i; `clr_sts_flag` 1 clears each axis's status first.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MovePtpPack8 {
    pub axis_mask: i16,
    pub clr_sts_flag: i16,
    pub acc: [f64; PACK8_AXES],
    pub dec: [f64; PACK8_AXES],
    pub start_vel: [f64; PACK8_AXES],
    pub end_vel: [f64; PACK8_AXES],
    pub max_vel: [f64; PACK8_AXES],
    pub smooth_coef: [i16; PACK8_AXES],
    pub tgt_pos: [i64; PACK8_AXES],
}

impl MovePtpPack8 {
    pub fn write(&self, w: &mut Writer) {
        w.i16(self.axis_mask).i16(self.clr_sts_flag);
        for v in [
            &self.acc,
            &self.dec,
            &self.start_vel,
            &self.end_vel,
            &self.max_vel,
        ] {
            put_f64s(w, v);
        }
        put_i16s(w, &self.smooth_coef);
        put_i64s(w, &self.tgt_pos);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<MovePtpPack8, PayloadError> {
        Ok(MovePtpPack8 {
            axis_mask: r.i16()?,
            clr_sts_flag: r.i16()?,
            acc: get_f64s(r)?,
            dec: get_f64s(r)?,
            start_vel: get_f64s(r)?,
            end_vel: get_f64s(r)?,
            max_vel: get_f64s(r)?,
            smooth_coef: get_i16s(r)?,
            tgt_pos: get_i64s(r)?,
        })
    }
}

/// `TAxisStsPack12Ex` (digest 001 §3.4): 12 axes' status words, motion I/O (active and
/// electrical level), planned and encoder positions and planned velocities, the two coordinate
/// systems, general and extension I/O, analog channels.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AxisStsPack12Ex {
    pub mt_sts: [i16; PACK12_AXES],
    pub mt_mio: [i16; PACK12_AXES],
    pub mt_mio_log: [i16; PACK12_AXES],
    pub mt_prf_pos: [i64; PACK12_AXES],
    pub mt_enc_pos: [i64; PACK12_AXES],
    /// `float` in C.
    pub mt_prf_vel: [f64; PACK12_AXES],
    pub crd_sts: [i16; 2],
    pub crd_prf_vel: [f64; 2],
    pub crd_user_seg: [i64; 2],
    pub crd_free_space: [i64; 2],
    pub crd_used_space: [i64; 2],
    pub gpi: i64,
    pub gpo: i64,
    pub crd_left_len: [i64; 2],
    pub crd_all_cmd_cnt: [i64; 2],
    pub ext_di: [i64; 6],
    pub ext_do: [i64; 6],
    pub adc: [i16; 4],
    pub adc_aux: [i16; 2],
    pub dac: [i16; 4],
    pub dac_aux: [i16; 2],
}

impl AxisStsPack12Ex {
    pub fn write(&self, w: &mut Writer) {
        put_i16s(w, &self.mt_sts);
        put_i16s(w, &self.mt_mio);
        put_i16s(w, &self.mt_mio_log);
        put_i64s(w, &self.mt_prf_pos);
        put_i64s(w, &self.mt_enc_pos);
        put_f64s(w, &self.mt_prf_vel);
        put_i16s(w, &self.crd_sts);
        put_f64s(w, &self.crd_prf_vel);
        put_i64s(w, &self.crd_user_seg);
        put_i64s(w, &self.crd_free_space);
        put_i64s(w, &self.crd_used_space);
        w.i64(self.gpi).i64(self.gpo);
        put_i64s(w, &self.crd_left_len);
        put_i64s(w, &self.crd_all_cmd_cnt);
        put_i64s(w, &self.ext_di);
        put_i64s(w, &self.ext_do);
        put_i16s(w, &self.adc);
        put_i16s(w, &self.adc_aux);
        put_i16s(w, &self.dac);
        put_i16s(w, &self.dac_aux);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<AxisStsPack12Ex, PayloadError> {
        Ok(AxisStsPack12Ex {
            mt_sts: get_i16s(r)?,
            mt_mio: get_i16s(r)?,
            mt_mio_log: get_i16s(r)?,
            mt_prf_pos: get_i64s(r)?,
            mt_enc_pos: get_i64s(r)?,
            mt_prf_vel: get_f64s(r)?,
            crd_sts: get_i16s(r)?,
            crd_prf_vel: get_f64s(r)?,
            crd_user_seg: get_i64s(r)?,
            crd_free_space: get_i64s(r)?,
            crd_used_space: get_i64s(r)?,
            gpi: r.i64()?,
            gpo: r.i64()?,
            crd_left_len: get_i64s(r)?,
            crd_all_cmd_cnt: get_i64s(r)?,
            ext_di: get_i64s(r)?,
            ext_do: get_i64s(r)?,
            adc: get_i16s(r)?,
            adc_aux: get_i16s(r)?,
            dac: get_i16s(r)?,
            dac_aux: get_i16s(r)?,
        })
    }
}

/// `TEstopExParam` (digest 001 §3.6): the axes an input stops, the input (type 0 general,
/// 1 negative limit, 2 positive limit, 3 home, 4 index; its channel), its filter [0, 255] and
/// the level that triggers (0 low, 1 high).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EstopExParam {
    pub ax_mask: i16,
    pub di_type: i16,
    pub di_index: i16,
    pub filter: i16,
    pub di_sense: i64,
}

impl EstopExParam {
    pub fn write(&self, w: &mut Writer) {
        w.i16(self.ax_mask)
            .i16(self.di_type)
            .i16(self.di_index)
            .i16(self.filter)
            .i64(self.di_sense);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<EstopExParam, PayloadError> {
        Ok(EstopExParam {
            ax_mask: r.i16()?,
            di_type: r.i16()?,
            di_index: r.i16()?,
            filter: r.i16()?,
            di_sense: r.i64()?,
        })
    }
}

/// `TDacMotor` (digest 001 §3.17): output inversion, zero-drift bias, output limit (32767 the
/// most).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DacMotor {
    pub inverse: i16,
    pub bias: i16,
    pub dac_lmt: i16,
}

impl DacMotor {
    pub fn write(&self, w: &mut Writer) {
        w.i16(self.inverse).i16(self.bias).i16(self.dac_lmt);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<DacMotor, PayloadError> {
        Ok(DacMotor {
            inverse: r.i16()?,
            bias: r.i16()?,
            dac_lmt: r.i16()?,
        })
    }
}

/// `TPidPara` (digest 001 §3.17): gains (`float` in C, f64 here) and limits.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PidPara {
    pub kp: f64,
    pub ki: f64,
    pub kd: f64,
    pub kvff: f64,
    pub integral_limit: i64,
    pub derivative_limit: i64,
    pub out_limit: i16,
}

impl PidPara {
    pub fn write(&self, w: &mut Writer) {
        w.f64(self.kp)
            .f64(self.ki)
            .f64(self.kd)
            .f64(self.kvff)
            .i64(self.integral_limit)
            .i64(self.derivative_limit)
            .i16(self.out_limit);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<PidPara, PayloadError> {
        Ok(PidPara {
            kp: r.f64()?,
            ki: r.f64()?,
            kd: r.f64()?,
            kvff: r.f64()?,
            integral_limit: r.i64()?,
            derivative_limit: r.i64()?,
            out_limit: r.i16()?,
        })
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn structs_round_trip() {
        let pack = MovePtpPack8 {
            axis_mask: 0b101,
            clr_sts_flag: 1,
            acc: [0.5; 8],
            max_vel: [10.0; 8],
            smooth_coef: [3; 8],
            tgt_pos: [-7, 1 << 40, 0, 0, 0, 0, 0, 9],
            ..Default::default()
        };
        let mut w = Writer::new();
        pack.write(&mut w);
        let mut r = Reader::new(&w.bytes);
        assert_eq!(MovePtpPack8::read(&mut r).unwrap(), pack);
        r.finish().unwrap();

        let sts = AxisStsPack12Ex {
            mt_sts: [3; 12],
            mt_prf_vel: [1.5; 12],
            gpi: -1,
            dac_aux: [4, 5],
            ..Default::default()
        };
        let mut w = Writer::new();
        sts.write(&mut w);
        let mut r = Reader::new(&w.bytes);
        assert_eq!(AxisStsPack12Ex::read(&mut r).unwrap(), sts);
        r.finish().unwrap();

        let e = EstopExParam {
            ax_mask: 6,
            di_type: 0,
            di_index: 2,
            filter: 10,
            di_sense: 1,
        };
        let mut w = Writer::new();
        e.write(&mut w);
        let mut r = Reader::new(&w.bytes);
        assert_eq!(EstopExParam::read(&mut r).unwrap(), e);
        r.finish().unwrap();

        let pid = PidPara {
            kp: 5.0,
            ki: 1.0,
            integral_limit: -3,
            out_limit: 32767,
            ..Default::default()
        };
        let mut w = Writer::new();
        pid.write(&mut w);
        DacMotor {
            inverse: 1,
            bias: -20,
            dac_lmt: 500,
        }
        .write(&mut w);
        let mut r = Reader::new(&w.bytes);
        assert_eq!(PidPara::read(&mut r).unwrap(), pid);
        assert_eq!(DacMotor::read(&mut r).unwrap().dac_lmt, 500);
        r.finish().unwrap();
    }
}

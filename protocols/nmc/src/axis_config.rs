//! The basic axis configuration's struct (digest 001 §3.6 `TSafePara`) as the wire carries it.

use crate::payload::{PayloadError, Reader, Writer};

/// `TSafePara`: estpDec, maxVel, maxAcc (pulse/ms², pulse/ms, pulse/ms²; defaults 32767, TV07).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SafePara {
    pub estp_dec: f64,
    pub max_vel: f64,
    pub max_acc: f64,
}

impl SafePara {
    pub fn write(&self, w: &mut Writer) {
        w.f64(self.estp_dec).f64(self.max_vel).f64(self.max_acc);
    }
    pub fn read(r: &mut Reader<'_>) -> Result<SafePara, PayloadError> {
        Ok(SafePara {
            estp_dec: r.f64()?,
            max_vel: r.f64()?,
            max_acc: r.f64()?,
        })
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn safe_para_round_trips() {
        let p = SafePara {
            estp_dec: 1.0,
            max_vel: 2.0,
            max_acc: 3.0,
        };
        let mut w = Writer::new();
        p.write(&mut w);
        let mut r = Reader::new(&w.bytes);
        assert_eq!(SafePara::read(&mut r).unwrap(), p);
        r.finish().unwrap();
    }
}

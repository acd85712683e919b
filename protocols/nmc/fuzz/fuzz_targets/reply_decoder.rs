//! Arbitrary bytes as the library receives replies: frames decoded in two chunks, then each
//! frame's payload read as the out arguments of the row its function id names (scalars,
//! strings, arrays, the manual's structs), as the shim's exports do. Never panics; a count
//! beyond the payload is an error, not an allocation.

#![no_main]

use libfuzzer_sys::fuzz_target;
use mcemu_nmc::frame::FrameDecoder;
use mcemu_nmc::payload::{PayloadError, Reader};
use mcemu_nmc::structs::{CardInfo, HomeSetting, JogPara, PtpPara};
use mcemu_nmc::sync_structs::{
    read_array, AdvCaptureParam, Comp2D, Comp2DTable, Comp2DimensParam, Comp2DimensSts, CompData,
    PtPara, PvtPara,
};
use mcemu_nmc::table::{self, CType};

fn read_outputs(f: &table::Function, r: &mut Reader<'_>) -> Result<(), PayloadError> {
    for a in f.outputs() {
        match a.ty {
            CType::Short | CType::UShort | CType::Hand | CType::SearchMode => {
                r.i16()?;
            }
            CType::Int | CType::UInt => {
                r.i32()?;
            }
            CType::Long | CType::ULong => {
                r.i64()?;
            }
            CType::UChar => {
                r.u8()?;
            }
            CType::Double => {
                r.f64()?;
            }
            CType::Str | CType::Ipv4 => {
                r.str()?;
            }
            CType::ShortArray => {
                read_array(r, |r| r.i16())?;
            }
            CType::LongArray => {
                read_array(r, |r| r.i64())?;
            }
            CType::ULongArray => {
                read_array(r, |r| r.u64())?;
            }
            CType::DoubleArray => {
                read_array(r, |r| r.f64())?;
            }
            CType::Bytes => {
                read_array(r, |r| r.u8())?;
            }
            CType::StructArray("TCompData") => {
                read_array(r, CompData::read)?;
            }
            CType::StructArray(_) => {
                read_array(r, |r| r.str().map(|_| ()))?;
            }
            CType::Struct(name) => match name {
                "TPtpPara" => {
                    let _ = PtpPara::read(r)?;
                }
                "TJogPara" => {
                    let _ = JogPara::read(r)?;
                }
                "THomeSetting" => {
                    let _ = HomeSetting::read(r)?;
                }
                "TCardInfo" => {
                    let _ = CardInfo::read(r)?;
                }
                "TPtPara" => {
                    let _ = PtPara::read(r)?;
                }
                "TPvtPara" => {
                    let _ = PvtPara::read(r)?;
                }
                "TAdvCaptureParam" => {
                    let _ = AdvCaptureParam::read(r)?;
                }
                "TComp2DimensParamEx" => {
                    let _ = Comp2DimensParam::read(r)?;
                }
                "TComp2DimensSts" => {
                    let _ = Comp2DimensSts::read(r)?;
                }
                "T2DCompensationTable" => {
                    let _ = Comp2DTable::read(r)?;
                }
                "T2DCompensation" => {
                    let _ = Comp2D::read(r)?;
                }
                _ => {}
            },
        }
    }
    r.finish()
}

fuzz_target!(|data: &[u8]| {
    let Some((&cut, bytes)) = data.split_first() else {
        return;
    };
    let (a, b) = bytes.split_at(usize::from(cut).min(bytes.len()));
    let mut d = FrameDecoder::new();
    for chunk in [a, b] {
        d.push(chunk);
        loop {
            match d.next_frame() {
                Ok(Some(frame)) => {
                    if let Some(f) = table::by_id(frame.header.function) {
                        let _ = read_outputs(f, &mut Reader::new(&frame.payload));
                    }
                }
                Ok(None) => break,
                Err(_) => return,
            }
        }
    }
});

//! The HMPL constants a call may name (`HOME_METHOD_33`, `BM_BUFF`, `CS_PCS` …). The manual
//! gives few of their numbers (digest 004 §7.1 item 5: only `SHAPER_NORMAL` = 1,
//! `SHAPER_ROBUST` = 0, `TRUE` = 1, `FALSE` = 0); the others are chosen here once, in table
//! order where the manual lists them, and recorded in docs/decisions.md ("HIMC Native ASCII").

/// A constant's value: an integer (flags combine with `|`) or a double (`PI`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ConstantValue {
    Int(i64),
    Double(f64),
}

/// `CS_WCS1` … `CS_WCS15` are `n << CS_WCS_SHIFT`.
pub const CS_WCS_SHIFT: u32 = 4;
/// `CS_PCS`: the product frame bit.
pub const CS_PCS: i64 = 0x1;
/// `CS_OFFSET`: the temporary-zero frame bit.
pub const CS_OFFSET: i64 = 0x2;
/// `CS_ACS`: axis coordinates.
pub const CS_ACS: i64 = 0x100;
/// `CS_GLOBAL` (not supported by the HIMC, §8.1.2).
pub const CS_GLOBAL: i64 = 0x200;
/// `HMPL_SLOT_n` is `n << SLOT_SHIFT`, or'ed into a slave id (§9.1).
pub const SLOT_SHIFT: u32 = 16;
/// `HMPL_DAC_SIGNED`, or'ed into a conversion type (§10.1).
pub const DAC_SIGNED: i64 = 0x100;
/// `HMPL_AXIS_n` is `n << AXIS_VAR_SHIFT`, or'ed with `HMPL_REF_POS` … (§10.4.1).
pub const AXIS_VAR_SHIFT: u32 = 8;

/// The constants with fixed names, in the manual's table order.
pub const CONSTANTS: &[(&str, ConstantValue)] = &[
    ("TRUE", ConstantValue::Int(1)),
    ("FALSE", ConstantValue::Int(0)),
    ("true", ConstantValue::Int(1)),
    ("false", ConstantValue::Int(0)),
    // §23.1.
    ("PI", ConstantValue::Double(std::f64::consts::PI)),
    ("SQRT2", ConstantValue::Double(std::f64::consts::SQRT_2)),
    (
        "SQRT1_2",
        ConstantValue::Double(std::f64::consts::FRAC_1_SQRT_2),
    ),
    // Table 8.1.4.1, velocity buffer modes, in table order.
    ("BM_BUFF", ConstantValue::Int(0)),
    ("BM_ABORT", ConstantValue::Int(1)),
    ("BM_LOW", ConstantValue::Int(2)),
    ("BM_PREV", ConstantValue::Int(3)),
    ("BM_NEXT", ConstantValue::Int(4)),
    ("BM_HIGH", ConstantValue::Int(5)),
    ("BM_LOOKAHEAD", ConstantValue::Int(6)),
    // Table 8.1.5.1, transition modes, in table order.
    ("TM_NONE", ConstantValue::Int(0)),
    ("TM_START_VEL", ConstantValue::Int(1)),
    ("TM_CONST_VEL", ConstantValue::Int(2)),
    ("TM_CORNER_DIST", ConstantValue::Int(3)),
    ("TM_MAX_CORNER_DEV", ConstantValue::Int(4)),
    ("TM_MAX_CORNER_CURV", ConstantValue::Int(5)),
    // Table 8.1.2.1, coordinate systems: bit flags (`CS_WCS1 | CS_PCS`); MCS is none of them.
    ("CS_MCS", ConstantValue::Int(0)),
    ("CS_PCS", ConstantValue::Int(CS_PCS)),
    ("CS_OFFSET", ConstantValue::Int(CS_OFFSET)),
    ("CS_ACS", ConstantValue::Int(CS_ACS)),
    ("CS_GLOBAL", ConstantValue::Int(CS_GLOBAL)),
    // §15.1 (the manual's own numbers).
    ("SHAPER_NORMAL", ConstantValue::Int(1)),
    ("SHAPER_ROBUST", ConstantValue::Int(0)),
    // Table 10.1.1, analog conversion types, in table order; SIGNED is a flag.
    ("HMPL_DAC_NONE", ConstantValue::Int(0)),
    ("HMPL_DAC_N10_P10", ConstantValue::Int(1)),
    ("HMPL_DAC_P0_P10", ConstantValue::Int(2)),
    ("HMPL_DAC_N5_P5", ConstantValue::Int(3)),
    ("HMPL_DAC_P0_P5", ConstantValue::Int(4)),
    ("HMPL_DAC_P0_P20", ConstantValue::Int(5)),
    ("HMPL_DAC_P4_P20", ConstantValue::Int(6)),
    ("HMPL_DAC_N20_P20", ConstantValue::Int(7)),
    ("HMPL_DAC_SIGNED", ConstantValue::Int(DAC_SIGNED)),
    // §10.4.1, the variables an analog output can follow (or'ed with `HMPL_AXIS_n`).
    ("HMPL_REF_POS", ConstantValue::Int(1)),
    ("HMPL_REF_VEL", ConstantValue::Int(2)),
    ("HMPL_REF_ACC", ConstantValue::Int(3)),
    ("HMPL_POS_FB", ConstantValue::Int(4)),
    ("HMPL_VEL_FB", ConstantValue::Int(5)),
    ("HMPL_ACC_FB", ConstantValue::Int(6)),
    ("HMPL_CUR_FB", ConstantValue::Int(7)),
];

/// The families `PREFIXn`: `HOME_METHOD_n` = n (CiA 402 method number, §20.3, 1 … 37),
/// `CS_WCSn` (1 … 15), `HMPL_SLOT_n` (1 … 15), `HMPL_AXIS_n` (0 … 15).
fn numbered(name: &str) -> Option<i64> {
    /// A family: its prefix, the numbers it has, the value of number n.
    type Family = (&'static str, std::ops::RangeInclusive<i64>, fn(i64) -> i64);
    let families: [Family; 4] = [
        ("HOME_METHOD_", 1..=37, |n| n),
        ("CS_WCS", 1..=15, |n| n << CS_WCS_SHIFT),
        ("HMPL_SLOT_", 1..=15, |n| n << SLOT_SHIFT),
        ("HMPL_AXIS_", 0..=15, |n| n << AXIS_VAR_SHIFT),
    ];
    families.iter().find_map(|(prefix, range, value)| {
        let digits = name.strip_prefix(prefix)?;
        // No sign, no leading zero: `HOME_METHOD_033` is not a name.
        if digits.is_empty() || digits.starts_with('0') && digits.len() > 1 {
            return None;
        }
        if !digits.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        let n: i64 = digits.parse().ok()?;
        range.contains(&n).then(|| value(n))
    })
}

/// The value of the constant called `name`, exactly as spelled.
pub fn constant(name: &str) -> Option<ConstantValue> {
    CONSTANTS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, v)| *v)
        .or_else(|| numbered(name).map(ConstantValue::Int))
}

/// The coordinate system of an HMPL `coord_sys` bitmask as the engine names it (`"mcs"`,
/// `"pcs"`, `"wcs1|pcs"`, `"offset|wcs2|pcs"`); `None` for masks the engine has no frame for
/// (ACS, GLOBAL, unknown bits, or a link without the PCS it hangs from).
pub fn coordinate_system_name(mask: i64) -> Option<String> {
    let wcs = (mask >> CS_WCS_SHIFT) & 0xf;
    let known = CS_PCS | CS_OFFSET | (0xf << CS_WCS_SHIFT);
    if mask & !known != 0 || mask < 0 {
        return None;
    }
    if mask == 0 {
        return Some("mcs".into());
    }
    if mask & CS_PCS == 0 {
        return None;
    }
    let mut parts = Vec::new();
    if mask & CS_OFFSET != 0 {
        parts.push("offset".to_string());
    }
    if wcs != 0 {
        parts.push(format!("wcs{wcs}"));
    }
    parts.push("pcs".into());
    Some(parts.join("|"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_have_the_chosen_numbers() {
        assert_eq!(constant("HOME_METHOD_33"), Some(ConstantValue::Int(33)));
        assert_eq!(constant("HOME_METHOD_37"), Some(ConstantValue::Int(37)));
        assert_eq!(constant("HOME_METHOD_38"), None);
        assert_eq!(constant("HOME_METHOD_033"), None);
        assert_eq!(constant("BM_LOOKAHEAD"), Some(ConstantValue::Int(6)));
        assert_eq!(constant("TM_NONE"), Some(ConstantValue::Int(0)));
        assert_eq!(constant("SHAPER_NORMAL"), Some(ConstantValue::Int(1)));
        assert_eq!(constant("CS_WCS2"), Some(ConstantValue::Int(0x20)));
        assert_eq!(constant("HMPL_SLOT_2"), Some(ConstantValue::Int(0x2_0000)));
        assert_eq!(constant("bm_buff"), None, "names are case-sensitive");
    }

    #[test]
    fn coordinate_masks_become_engine_frames() {
        let wcs1 = 1 << CS_WCS_SHIFT;
        let wcs2 = 2 << CS_WCS_SHIFT;
        assert_eq!(coordinate_system_name(0).as_deref(), Some("mcs"));
        assert_eq!(coordinate_system_name(CS_PCS).as_deref(), Some("pcs"));
        assert_eq!(
            coordinate_system_name(wcs1 | CS_PCS).as_deref(),
            Some("wcs1|pcs")
        );
        assert_eq!(
            coordinate_system_name(CS_OFFSET | wcs2 | CS_PCS).as_deref(),
            Some("offset|wcs2|pcs")
        );
        assert_eq!(coordinate_system_name(CS_ACS), None);
        assert_eq!(coordinate_system_name(wcs1), None);
    }
}

//! CRC of SDO block transfers (CiA 301 §7.2.4.3.16): CRC-16-CCITT, polynomial
//! x^16 + x^12 + x^5 + 1 (0x1021), initial value 0, no reflection, no final XOR.

const TABLE: [u16; 256] = table();

const fn table() -> [u16; 256] {
    let mut t = [0u16; 256];
    let mut i = 0;
    while i < 256 {
        let mut c = (i as u16) << 8;
        let mut bit = 0;
        while bit < 8 {
            c = if c & 0x8000 != 0 {
                (c << 1) ^ 0x1021
            } else {
                c << 1
            };
            bit += 1;
        }
        t[i] = c;
        i += 1;
    }
    t
}

/// Continue a CRC over `data`.
pub fn update(mut crc: u16, data: &[u8]) -> u16 {
    for &b in data {
        let i = usize::from((crc >> 8) as u8 ^ b);
        crc = (crc << 8) ^ TABLE.get(i).copied().unwrap_or(0);
    }
    crc
}

/// The block transfer CRC of `data`.
pub fn crc16(data: &[u8]) -> u16 {
    update(0, data)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn check_value_and_incremental_update() {
        // The CRC-16/XMODEM check value.
        assert_eq!(crc16(b"123456789"), 0x31C3);
        assert_eq!(crc16(b""), 0);
        assert_eq!(update(crc16(b"1234"), b"56789"), 0x31C3);
    }
}

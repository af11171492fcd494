//! A zip archive of stored (uncompressed) files, as the learning-management systems import
//! question packages. Deterministic: the files in the order given, every date 1980-01-01, no
//! extra fields, so the same files make the same bytes.

/// The archive of `files` (path inside the archive, bytes), in their order: at most 65,535
/// files of under 4 GiB in all (no zip64), which the callers keep to.
pub fn stored(files: &[(String, Vec<u8>)]) -> Vec<u8> {
    assert!(
        files.len() <= usize::from(u16::MAX),
        "a zip without zip64 holds at most 65,535 files"
    );
    let mut out = Vec::new();
    let mut central = Vec::new();
    for (name, data) in files {
        let offset = out.len() as u32;
        let crc = crc32(data);
        let size = data.len() as u32;
        // Local header: signature, version 2.0, flags (bit 11: the name is UTF-8), method 0
        // (stored), time 00:00, date 1980-01-01, CRC, both sizes, the name's length, no extra.
        out.extend_from_slice(&0x0403_4b50u32.to_le_bytes());
        let common = |v: &mut Vec<u8>| {
            v.extend_from_slice(&20u16.to_le_bytes());
            v.extend_from_slice(&0x0800u16.to_le_bytes());
            v.extend_from_slice(&0u16.to_le_bytes());
            v.extend_from_slice(&0u16.to_le_bytes());
            v.extend_from_slice(&0x0021u16.to_le_bytes());
            v.extend_from_slice(&crc.to_le_bytes());
            v.extend_from_slice(&size.to_le_bytes());
            v.extend_from_slice(&size.to_le_bytes());
            v.extend_from_slice(&(name.len() as u16).to_le_bytes());
            v.extend_from_slice(&0u16.to_le_bytes());
        };
        common(&mut out);
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(data);
        // Central directory entry: signature, version made by, then as the local header, then
        // no comment, disk 0, no attributes, and where the local header is.
        central.extend_from_slice(&0x0201_4b50u32.to_le_bytes());
        central.extend_from_slice(&20u16.to_le_bytes());
        common(&mut central);
        central.extend_from_slice(&[0; 6]);
        central.extend_from_slice(&0u32.to_le_bytes());
        central.extend_from_slice(&offset.to_le_bytes());
        central.extend_from_slice(name.as_bytes());
    }
    let start = out.len() as u32;
    out.extend_from_slice(&central);
    // End of central directory: one disk, the count twice, its size and start, no comment.
    out.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    out.extend_from_slice(&[0; 4]);
    out.extend_from_slice(&(files.len() as u16).to_le_bytes());
    out.extend_from_slice(&(files.len() as u16).to_le_bytes());
    out.extend_from_slice(&(central.len() as u32).to_le_bytes());
    out.extend_from_slice(&start.to_le_bytes());
    out.extend_from_slice(&0u16.to_le_bytes());
    out
}

/// CRC-32 (IEEE 802.3, reflected), as zip stores it.
fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in data {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc32_of_the_check_string() {
        // The standard check value of CRC-32/ISO-HDLC.
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
    }

    #[test]
    fn an_archive_lists_its_files_where_they_are() {
        let zip = stored(&[("a.txt".into(), b"hi".to_vec()), ("b/c".into(), vec![])]);
        // Two local headers, two central entries and the end record.
        assert_eq!(&zip[..4], b"PK\x03\x04");
        let end = zip.len() - 22;
        assert_eq!(&zip[end..end + 4], b"PK\x05\x06");
        assert_eq!(u16::from_le_bytes([zip[end + 10], zip[end + 11]]), 2);
        let start = u32::from_le_bytes(zip[end + 16..end + 20].try_into().unwrap()) as usize;
        assert_eq!(&zip[start..start + 4], b"PK\x01\x02");
        // The central entry is 46 bytes and its name; the second names its local header.
        let second = start + 46 + 5;
        assert_eq!(&zip[second..second + 4], b"PK\x01\x02");
        let at = u32::from_le_bytes(zip[second + 42..second + 46].try_into().unwrap()) as usize;
        assert_eq!(at, 30 + 5 + 2);
        assert_eq!(&zip[second + 46..second + 49], b"b/c");
        // The first file's data follows its 30-byte header and its name.
        assert_eq!(&zip[30 + 5..30 + 7], b"hi");
    }
}

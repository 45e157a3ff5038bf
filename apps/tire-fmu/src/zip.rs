//! A minimal ZIP writer of stored (uncompressed) entries, enough for an FMU (FMI 3.0 §2.5: a
//! ZIP file, APPNOTE.TXT 6.3 (PKWARE): local file headers, the central directory and its end
//! record; no compression, no ZIP64, so each entry and the whole archive must stay below
//! 4 GiB).

/// The ZIP archive of `entries` (name, bytes), stored. Errors: an entry or the archive of
/// 4 GiB or more, or more than 65535 entries.
pub fn stored(entries: &[(String, &[u8])]) -> Result<Vec<u8>, String> {
    let small = |n: usize, what: &str| {
        u32::try_from(n).map_err(|_| format!("{what} of {n} bytes is too large for ZIP"))
    };
    if entries.len() > u16::MAX as usize {
        return Err(format!("{} entries, at most 65535", entries.len()));
    }
    let mut out = Vec::new();
    let mut central = Vec::new();
    // 1980-01-01 00:00 (MS-DOS date and time)
    let (time, date) = (0u16, (1u16 << 5) | 1);
    for (name, data) in entries {
        let offset = small(out.len(), "archive")?;
        // CRC-32 (IEEE 802.3), as the ZIP format requires
        let (crc, size) = (crc32fast::hash(data), small(data.len(), name)?);
        let n = name.len() as u16;
        // local file header
        out.extend_from_slice(&0x0403_4b50u32.to_le_bytes());
        for v in [20u16, 0, 0, time, date] {
            out.extend_from_slice(&v.to_le_bytes());
        }
        for v in [crc, size, size] {
            out.extend_from_slice(&v.to_le_bytes());
        }
        out.extend_from_slice(&n.to_le_bytes());
        out.extend_from_slice(&0u16.to_le_bytes());
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(data);
        // its central directory record
        central.extend_from_slice(&0x0201_4b50u32.to_le_bytes());
        for v in [20u16, 20, 0, 0, time, date] {
            central.extend_from_slice(&v.to_le_bytes());
        }
        for v in [crc, size, size] {
            central.extend_from_slice(&v.to_le_bytes());
        }
        for v in [n, 0, 0, 0, 0] {
            central.extend_from_slice(&v.to_le_bytes());
        }
        central.extend_from_slice(&0u32.to_le_bytes());
        central.extend_from_slice(&offset.to_le_bytes());
        central.extend_from_slice(name.as_bytes());
    }
    let cd_offset = small(out.len(), "archive")?;
    let cd_size = small(central.len(), "central directory")?;
    out.extend_from_slice(&central);
    small(out.len(), "archive")?;
    let count = entries.len() as u16;
    out.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    for v in [0u16, 0, count, count] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(&cd_size.to_le_bytes());
    out.extend_from_slice(&cd_offset.to_le_bytes());
    out.extend_from_slice(&0u16.to_le_bytes());
    Ok(out)
}

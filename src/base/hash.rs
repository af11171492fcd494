//! The content hash behind scene identity and the build cache's keys.

/// FNV-1a, 64 bits: stable across runs, platforms and Rust releases (std's hasher is not).
pub fn content_hash(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(*b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

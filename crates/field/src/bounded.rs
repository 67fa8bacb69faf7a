//! Bounded reading of field data files: the `platoonsim-bounded` crate (its gzip mode, in
//! `input.rs`), and the field data's own limits.

/// The largest field file opened (as stored, gzip or not): 16 GiB, a year of a district's
/// PeMS station_5min files in one.
pub const MAX_FILE_BYTES: u64 = 16 << 30;
/// The most text a file may decompress to: 64 GiB (a gzip stream that inflates beyond is
/// refused rather than read to the end).
pub const MAX_TEXT_BYTES: u64 = 64 << 30;
/// The longest line: 64 KiB (a PeMS row is under 2 KiB even with every lane's columns).
pub const MAX_LINE_BYTES: usize = 64 << 10;

//! The binary block of the page: named sections of little-endian numbers, concatenated,
//! gzip-compressed and base64-encoded. The page lists the sections (name, element type,
//! length) in its JSON block and inflates the block with the browser's `DecompressionStream`.

use base64::Engine as _;
use flate2::{write::GzEncoder, Compression};
use serde::Serialize;
use std::io::Write;

/// One section: its name, element type (`u32`, `i32`, `u8`) and element count.
#[derive(Debug, Serialize, Clone)]
pub struct Section {
    pub name: &'static str,
    #[serde(rename = "type")]
    pub kind: &'static str,
    pub len: usize,
}

#[derive(Default)]
pub struct Blob {
    pub sections: Vec<Section>,
    data: Vec<u8>,
}

impl Blob {
    pub fn u32s(&mut self, name: &'static str, v: &[u32]) {
        self.push(name, "u32", v.len(), v.iter().flat_map(|x| x.to_le_bytes()));
    }

    pub fn i32s(&mut self, name: &'static str, v: &[i32]) {
        self.push(name, "i32", v.len(), v.iter().flat_map(|x| x.to_le_bytes()));
    }

    pub fn bytes(&mut self, name: &'static str, v: &[u8]) {
        self.push(name, "u8", v.len(), v.iter().copied());
    }

    fn push(
        &mut self,
        name: &'static str,
        kind: &'static str,
        len: usize,
        b: impl Iterator<Item = u8>,
    ) {
        // Typed arrays need their start aligned to the element size.
        self.data.resize(self.data.len().next_multiple_of(4), 0);
        self.data.extend(b);
        self.sections.push(Section { name, kind, len });
    }

    /// The raw bytes of a section (for tests).
    #[cfg(test)]
    pub fn section(&self, name: &str) -> Option<&[u8]> {
        let mut at: usize = 0;
        for s in &self.sections {
            at = at.next_multiple_of(4);
            let size = s.len * if s.kind == "u8" { 1 } else { 4 };
            if s.name == name {
                return Some(&self.data[at..at + size]);
            }
            at += size;
        }
        None
    }

    /// Raw (uncompressed) size in bytes (for tests).
    #[cfg(test)]
    pub fn raw_len(&self) -> usize {
        self.data.len()
    }

    /// gzip, then base64 (standard alphabet, padded).
    pub fn encode(&self) -> String {
        let mut gz = GzEncoder::new(Vec::new(), Compression::best());
        gz.write_all(&self.data).expect("writing to memory");
        let bytes = gz.finish().expect("writing to memory");
        base64::engine::general_purpose::STANDARD.encode(bytes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use flate2::read::GzDecoder;
    use std::io::Read;

    #[test]
    fn sections_are_aligned_and_round_trip() {
        let mut b = Blob::default();
        b.bytes("a", &[1, 2, 3]);
        b.u32s("b", &[0x0102_0304]);
        b.i32s("c", &[-2]);
        assert_eq!(b.section("a"), Some(&[1u8, 2, 3][..]));
        // "b" starts at 4, after one byte of padding.
        assert_eq!(b.section("b"), Some(&[4u8, 3, 2, 1][..]));
        assert_eq!(b.section("c"), Some(&(-2i32).to_le_bytes()[..]));
        assert_eq!(b.raw_len(), 12);
        let gz = base64::engine::general_purpose::STANDARD
            .decode(b.encode())
            .unwrap();
        let mut raw = Vec::new();
        GzDecoder::new(&gz[..]).read_to_end(&mut raw).unwrap();
        assert_eq!(raw, b.data);
    }
}

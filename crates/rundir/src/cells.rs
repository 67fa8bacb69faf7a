//! The word cells of the detector records, typed: what `detectors.csv` writes in its `lane`
//! and `kind` columns, and what the readers match on.

use std::fmt;
use std::str::FromStr;

/// The `lane` cell of a detector record: the cross-section (`all`, every lane together) or one
/// lane, counted from the right from 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Lane {
    All,
    Index(u32),
}

impl Lane {
    /// The text of the cross-section.
    pub const ALL: &'static str = "all";

    /// Whether `cell` is the cross-section's text (the readers' filter, without parsing).
    pub fn is_all(cell: &str) -> bool {
        cell == Lane::ALL
    }
}

impl fmt::Display for Lane {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Lane::All => f.write_str(Lane::ALL),
            Lane::Index(n) => write!(f, "{n}"),
        }
    }
}

impl FromStr for Lane {
    type Err = String;

    fn from_str(s: &str) -> Result<Lane, String> {
        if s == Lane::ALL {
            return Ok(Lane::All);
        }
        match s.parse::<u32>() {
            Ok(n) if n >= 1 && s.bytes().all(|b| b.is_ascii_digit()) => Ok(Lane::Index(n)),
            _ => Err(format!(
                "'{s}' is not a lane: `all` or a lane number counted from the right (1, 2, ...)"
            )),
        }
    }
}

/// The `kind` cell of a detector record: where the detector stands. In `road.json` it is the
/// same word (serde's kebab case of the variant is [`DetectorKind::as_str`]).
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum DetectorKind {
    Mainline,
    OnRamp,
    OffRamp,
}

impl DetectorKind {
    pub const ALL: [DetectorKind; 3] = [
        DetectorKind::Mainline,
        DetectorKind::OnRamp,
        DetectorKind::OffRamp,
    ];

    pub fn as_str(self) -> &'static str {
        match self {
            DetectorKind::Mainline => "mainline",
            DetectorKind::OnRamp => "on-ramp",
            DetectorKind::OffRamp => "off-ramp",
        }
    }
}

impl fmt::Display for DetectorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl FromStr for DetectorKind {
    type Err = String;

    fn from_str(s: &str) -> Result<DetectorKind, String> {
        DetectorKind::ALL
            .into_iter()
            .find(|k| k.as_str() == s)
            .ok_or_else(|| format!("'{s}' is not a detector kind: mainline, on-ramp or off-ramp"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_read_back_as_they_are_written() {
        // The text is part of the golden digests: it must stay exactly this.
        assert_eq!(Lane::All.to_string(), "all");
        assert_eq!(Lane::Index(3).to_string(), "3");
        for lane in [Lane::All, Lane::Index(1), Lane::Index(12)] {
            assert_eq!(lane.to_string().parse::<Lane>(), Ok(lane));
        }
        for bad in ["0", "", "All", "+1", "1.0", "-2"] {
            assert!(bad.parse::<Lane>().is_err(), "{bad}");
        }
        for k in DetectorKind::ALL {
            assert_eq!(k.to_string().parse::<DetectorKind>(), Ok(k));
        }
        assert_eq!(DetectorKind::OnRamp.as_str(), "on-ramp");
        for k in DetectorKind::ALL {
            let json = serde_json::to_string(&k).unwrap();
            assert_eq!(json, format!("\"{k}\""));
            assert_eq!(serde_json::from_str::<DetectorKind>(&json).unwrap(), k);
        }
        assert!("onramp".parse::<DetectorKind>().is_err());
    }
}

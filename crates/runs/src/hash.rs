//! Stable run keys: FNV-1a (64 bit) of the resolved configuration's JSON.
//!
//! The JSON of a [`Config`] lists its fields in declaration order and prints numbers in
//! their shortest round-trip form, so the same configuration gives the same key on every
//! machine, thread count and run. The seed is part of the configuration, so each run of a
//! cell has its own key. A change of the configuration's shape (a new field) changes every
//! key, which is the safe direction: stale results are recomputed, never reused.

use platoonsim_sim::Config;

const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

/// FNV-1a, 64 bit.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    let mut h = FNV_OFFSET;
    for &b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(FNV_PRIME);
    }
    h
}

/// The compact JSON that the key is computed from.
pub fn config_json(config: &Config) -> Vec<u8> {
    serde_json::to_vec(config).expect("a Config always serializes to JSON")
}

/// The run key of a configuration: 16 lower-case hex digits of [`fnv1a64`] of its JSON.
pub fn config_key(config: &Config) -> String {
    format!("{:016x}", fnv1a64(&config_json(config)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a64_reference_vectors() {
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn key_is_stable_and_seed_sensitive() {
        let a = Config::homogeneous(0.5, 1000.0, 600.0, 120.0, 1);
        let b = Config::homogeneous(0.5, 1000.0, 600.0, 120.0, 1);
        let c = Config::homogeneous(0.5, 1000.0, 600.0, 120.0, 2);
        let ka = config_key(&a);
        assert_eq!(ka.len(), 16);
        assert!(ka
            .chars()
            .all(|ch| ch.is_ascii_hexdigit() && !ch.is_ascii_uppercase()));
        assert_eq!(ka, config_key(&b));
        assert_ne!(ka, config_key(&c));
        // Any field counts, not only the seed.
        let mut d = a.clone();
        d.demand.vph_per_lane = 1000.5;
        assert_ne!(ka, config_key(&d));
        // The key is a pure function of the JSON text.
        assert_eq!(ka, format!("{:016x}", fnv1a64(&config_json(&a))));
    }

    #[test]
    fn key_does_not_depend_on_the_thread() {
        let cfg = Config::homogeneous(0.25, 2000.0, 300.0, 60.0, 7);
        let here = config_key(&cfg);
        let there = std::thread::spawn(move || config_key(&cfg)).join().unwrap();
        assert_eq!(here, there);
    }
}

//! A run's one-paragraph summary and its collision warning. The run directory itself is
//! written by `platoonsim_runs::run_dir` (the one writer, shared with the Python binding),
//! with the names and columns of `platoonsim_rundir`.

use platoonsim_sim::CollisionEvent;

mod paragraph;

pub use paragraph::{paragraph, si};

/// One line about the first collision, for the warning on stderr: time, kind, lane, place and
/// the vehicles involved.
pub fn describe_collision(e: &CollisionEvent) -> String {
    let who = match (e.other, e.other_kind) {
        (Some(o), Some(k)) => format!(
            "{} {} ({:.1} m/s) ran into {k} {o} ({:.1} m/s)",
            e.vehicle_kind,
            e.vehicle,
            e.v_mps,
            e.other_v_mps.unwrap_or(f64::NAN)
        ),
        _ => format!(
            "{} {} ({:.1} m/s) reached the end of its lane",
            e.vehicle_kind, e.vehicle, e.v_mps
        ),
    };
    format!(
        "t = {} s, {} in lane {} at x = {:.1} m: {who}, overlap {:.2} m",
        e.t_s,
        e.kind.as_str(),
        e.lane,
        e.x_m,
        e.overlap_m
    )
}

#[cfg(test)]
mod tests {
    use super::paragraph::wrap;
    use super::*;
    use platoonsim_sim::{Config, Output};
    use std::path::Path;

    /// A real five-minute run of the homogeneous road.
    fn short_run() -> (Config, Output) {
        let o = platoonsim_scenario::Overrides {
            duration_s: Some(300.0),
            warmup_s: Some(60.0),
            ..Default::default()
        };
        let config = platoonsim_scenario::load_with("homogeneous", &o).unwrap();
        let out = platoonsim_sim::run(&config, None).unwrap();
        (config, out)
    }

    #[test]
    fn paragraph_mentions_the_key_figures() {
        let (config, out) = short_run();
        let s = &out.summary;
        let p = paragraph(&config, s, Path::new("out/run"));
        let flat = p.replace('\n', " ");
        let discharge = format!("{:.1} veh/h/lane", s.discharge_flow_vphpl);
        let entered = format!("{} entered", s.vehicles_entered);
        for part in [
            "homogeneous:",
            "50 % CAV",
            "2500 veh/h/lane demand",
            "detector 'discharge'",
            &discharge,
            &entered,
            "out/run",
        ] {
            assert!(flat.contains(part), "{part} missing in:\n{p}");
        }
        assert!(p.lines().all(|l| l.len() <= 96), "{p}");
    }

    #[test]
    fn paragraph_of_a_network_run_gives_its_demand_scale_and_exits() {
        let o = platoonsim_scenario::Overrides {
            duration_s: Some(60.0),
            penetration: Some(0.4),
            ..Default::default()
        };
        let config = platoonsim_scenario::load_with("sr99", &o).unwrap();
        let out = platoonsim_sim::run(&config, None).unwrap();
        let p = paragraph(&config, &out.summary, Path::new("out/run")).replace('\n', " ");
        for part in [
            "sr99:",
            "40 % CAV, the network's demand x 1.210,",
            "Network discharge (off-ramps and the end):",
            "missed exits",
        ] {
            assert!(p.contains(part), "{part} missing in:\n{p}");
        }
        assert!(!p.contains("veh/h/lane demand"), "{p}");
    }

    #[test]
    fn the_warning_line_of_a_collision() {
        use platoonsim_sim::CollisionKind;
        let rear = CollisionEvent {
            t_s: 61.3,
            kind: CollisionKind::RearEnd,
            lane: 2,
            x_m: 4020.5,
            vehicle: 17,
            vehicle_kind: "human",
            v_mps: 12.25,
            other: Some(15),
            other_kind: Some("cav"),
            other_v_mps: Some(3.5),
            overlap_m: 0.125,
        };
        let end = CollisionEvent {
            kind: CollisionKind::LaneEnd,
            other: None,
            other_kind: None,
            other_v_mps: None,
            ..rear.clone()
        };
        assert_eq!(
            describe_collision(&rear),
            "t = 61.3 s, rear-end in lane 2 at x = 4020.5 m: human 17 (12.2 m/s) ran into cav 15 \
             (3.5 m/s), overlap 0.12 m"
        );
        assert_eq!(
            describe_collision(&end),
            "t = 61.3 s, lane-end in lane 2 at x = 4020.5 m: human 17 (12.2 m/s) reached the end \
             of its lane, overlap 0.12 m"
        );
    }

    #[test]
    fn wrap_keeps_words_and_width() {
        let w = wrap("aaa bbb ccc ddd", 7);
        assert_eq!(w, "aaa bbb\nccc ddd");
        assert_eq!(si(12_345_678.0), "12.35 M");
        assert_eq!(si(950.0), "950");
    }
}

//! `platoonsim calibrate` on the tests' corridor (`tests/calibrate/corridor.toml`) against
//! "field" data made by platoonsim itself with known parameter values: the fit recovers them;
//! the trace and the result are the same at any --jobs, sharded over processes, and on rerun
//! (which computes nothing); bad parameters files are errors naming the key and value.

mod common;

use common::calibrate::{dir, field, field_of, scenario, BUFFER_S, SPEED_KMH};
use common::{platoonsim, read_csv, s, scratch, stderr, stdout};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Instant;

fn calibrate(field: &Path, params: &str, out: &Path, extra: &[&str]) -> std::process::Output {
    let params = dir().join(params);
    let scenario = scenario();
    let mut args = vec![
        "-q",
        "calibrate",
        &scenario,
        "--field",
        s(field),
        "--params",
        s(&params),
        "--out",
        s(out),
    ];
    args.extend_from_slice(extra);
    let o = platoonsim(&args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    o
}

/// The known answer. Tolerance: |buffer − 0.4| ≤ 0.06 s and |mean − 100| ≤ 4 km/h, from a
/// start 0.3 s and 10 km/h away. Achievable because the objective at the field's values is
/// at its replication-noise floor (the mean of 3 seeds against the mean of 6 others), and
/// it rises above that floor by more than the noise (±0.015 between points 0.002 s apart)
/// once the buffer is 0.08 s or the speed 6 km/h off; measured with optimizer seeds 1-5,
/// every fit ended within 0.04 s and 3 km/h.
#[test]
fn calibration_recovers_the_field_parameters() {
    let d = scratch("known");
    let field = field(&d);
    let start = Instant::now();
    let o = calibrate(&field, "known.toml", &d.join("out"), &["--jobs", "2"]);
    let wall = start.elapsed().as_secs_f64();
    let out = d.join("out/known");
    let trace = read_csv(&out.join("trace.csv"));
    // The start point, then 14 generations of 6.
    assert_eq!(trace.len(), 1 + 84);
    assert_eq!(trace[0]["human.buffer_s"], "0.1");
    assert_eq!(trace[0]["human.desired_speed_kmh.mean"], "110");
    let obj = |r: &std::collections::HashMap<String, String>| common::num(r, "objective");
    let best = trace
        .iter()
        .min_by(|a, b| obj(a).total_cmp(&obj(b)))
        .unwrap();
    let (buffer, speed) = (
        common::num(best, "human.buffer_s"),
        common::num(best, "human.desired_speed_kmh.mean"),
    );
    eprintln!(
        "calibrated in {wall:.1} s: buffer {buffer:.3} s, desired speed mean {speed:.1} km/h, \
         objective {} (start {})",
        obj(best),
        obj(&trace[0])
    );
    assert!((buffer - BUFFER_S).abs() <= 0.06, "buffer {buffer}");
    assert!(
        (speed - SPEED_KMH).abs() <= 4.0,
        "desired speed mean {speed}"
    );
    assert!(obj(best) < 0.5 * obj(&trace[0]));
    assert!(
        stdout(&o).contains("85 candidates, 255 runs (255 computed, 0 reused)"),
        "{}",
        stdout(&o)
    );

    // calibrated.toml loads and validates, with the best values in it, exactly.
    let cal = platoonsim_scenario::load(s(&out.join("calibrated.toml"))).unwrap();
    assert_eq!(cal.human.buffer_s, buffer);
    assert_eq!(cal.human.desired_speed_kmh.mean, speed);
    assert_eq!(cal.clock_start_s, Some(7 * 3600));
    for f in [
        "convergence.png",
        "convergence.svg",
        "fit-before.md",
        "fit-after.md",
    ] {
        assert!(out.join(f).is_file(), "{f}");
    }
    let after = std::fs::read_to_string(out.join("fit-after.md")).unwrap();
    assert!(after.contains("| s2 | 4 |"), "{after}");
    let run: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("run.json")).unwrap()).unwrap();
    assert_eq!(run["best"]["values"]["human.buffer_s"], buffer);
    assert_eq!(run["field_files"][0]["path"], s(&field));
    assert_eq!(run["field_files"][0]["fnv1a64"].as_str().unwrap().len(), 16);
}

/// Same trace and result at --jobs 1 and 2, sharded over two concurrent processes (then an
/// unsharded run that computes nothing and writes the outputs), and on rerun.
#[test]
fn trace_is_the_same_at_any_jobs_and_sharding() {
    let d = scratch("determinism");
    let field = field(&d);
    let files = ["trace.csv", "calibrated.toml"];
    let read = |out: &Path| -> Vec<Vec<u8>> {
        files
            .iter()
            .map(|f| std::fs::read(out.join("small").join(f)).unwrap())
            .collect()
    };
    let one = d.join("jobs1");
    let o = calibrate(&field, "small.toml", &one, &["--jobs", "1"]);
    assert!(
        stdout(&o).contains("13 candidates, 26 runs (26 computed, 0 reused)"),
        "{}",
        stdout(&o)
    );
    let two = d.join("jobs2");
    calibrate(&field, "small.toml", &two, &["--jobs", "2"]);
    assert!(read(&one) == read(&two), "--jobs 1 and 2 differ");

    // Two shards at once into one directory, each waiting for the other's runs.
    let sharded = d.join("sharded");
    let params = dir().join("small.toml");
    let shards: Vec<std::process::Child> = ["1/2", "2/2"]
        .iter()
        .map(|sh| {
            Command::new(env!("CARGO_BIN_EXE_platoonsim"))
                .args(["-q", "calibrate", &scenario(), "--field", s(&field)])
                .args(["--params", s(&params), "--out", s(&sharded)])
                .args(["--shard", sh, "--jobs", "1", "--stale-after", "120"])
                .stdout(Stdio::piped())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap()
        })
        .collect();
    let mut computed = 0;
    for (i, c) in shards.into_iter().enumerate() {
        let o = c.wait_with_output().unwrap();
        assert!(o.status.success(), "shard {}: {}", i + 1, stderr(&o));
        let text = stdout(&o);
        assert!(
            text.contains(&format!(
                "shard {}/2: 13 candidates, 13 runs (13 computed, 0 reused)",
                i + 1
            )),
            "{text}"
        );
        computed += 13;
        assert!(!sharded.join("small/trace.csv").exists());
    }
    assert_eq!(computed, 26);
    let o = calibrate(&field, "small.toml", &sharded, &[]);
    assert!(
        stdout(&o).contains("26 runs (0 computed, 26 reused)"),
        "{}",
        stdout(&o)
    );
    assert!(
        read(&sharded) == read(&one),
        "sharded differs from unsharded"
    );

    // A shard alone, its peer never started: after the stale wait it computes the peer's runs
    // too, and the result is the same.
    let alone = d.join("alone");
    let o = calibrate(
        &field,
        "small.toml",
        &alone,
        &["--shard", "2/2", "--stale-after", "0.5"],
    );
    assert!(
        stdout(&o).contains("shard 2/2: 13 candidates, 26 runs (26 computed, 0 reused)"),
        "{}",
        stdout(&o)
    );
    let o = calibrate(&field, "small.toml", &alone, &[]);
    assert!(
        stdout(&o).contains("26 runs (0 computed, 26 reused)"),
        "{}",
        stdout(&o)
    );
    assert!(read(&alone) == read(&one), "a shard alone differs");

    // A rerun reuses every run file.
    let o = calibrate(&field, "small.toml", &one, &["--jobs", "2"]);
    assert!(
        stdout(&o).contains("(0 computed, 26 reused)"),
        "{}",
        stdout(&o)
    );
    assert!(read(&one) == read(&two));
}

/// `[demand]`: the entrance demands and exit fractions are estimated from the counts and set
/// in every candidate and in calibrated.toml. The corridor's true demand is 1,600 veh/h at
/// the entrance for the first 20 minutes and 15 % exiting at `off` throughout; the estimate is
/// the balance of the counts with the vehicles stored on the road (the first interval starts
/// on an empty road that fills): within 6 % at the entrance, within 0.01 for the fraction,
/// whose counts are direct.
#[test]
fn demand_step_sets_the_estimated_series() {
    let d = scratch("demand");
    let field = field_of(&d, &|_| true);
    let p = d.join("demand.toml");
    std::fs::write(
        &p,
        "name = \"dem\"\nreplications = 1\nbudget = 4\npopulation = 4\n[params]\n\
         \"human.buffer_s\" = { min = 0.0, max = 0.8 }\n[demand]\n\"off\" = \"off-off\"\n",
    )
    .unwrap();
    let o = platoonsim(&[
        "-q",
        "calibrate",
        &scenario(),
        "--field",
        s(&field),
        "--params",
        s(&p),
        "--out",
        s(&d),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let est = read_csv(&d.join("dem/demand.csv"));
    assert_eq!(est.len(), 2);
    assert_eq!(est[0]["time"], "07:00:00");
    let cal = platoonsim_scenario::load(s(&d.join("dem/calibrated.toml"))).unwrap();
    let net = cal.road.network.unwrap();
    for (k, row) in est.iter().enumerate() {
        assert_eq!(net.mainline_vph[k], common::num(row, "mainline_vph"));
        assert_eq!(net.on_ramps[0].demand_vph[k], common::num(row, "on_vph"));
        assert_eq!(
            net.off_ramps[0].exit_fraction[k],
            common::num(row, "off_exit_fraction")
        );
        assert!(
            (common::num(row, "off_exit_fraction") - 0.15).abs() < 0.01,
            "{row:?}"
        );
    }
    let q0 = common::num(&est[0], "mainline_vph");
    assert!((q0 - 1600.0).abs() < 0.06 * 1600.0, "{q0}");
    assert_eq!(net.demand_scale, 1.0);

    // Placed by a station table at the detectors' positions: the same estimate; without the
    // upstream station s1 the entrance is read from the next stations (a different estimate).
    let table = |rows: &str| {
        let t = d.join("stations.csv");
        std::fs::write(&t, format!("station,x_m,kind\n{rows}")).unwrap();
        let out = d.join("placed");
        let o = platoonsim(&[
            "-q",
            "calibrate",
            &scenario(),
            "--field",
            s(&field),
            "--params",
            s(&p),
            "--out",
            s(&out),
            "--stations",
            s(&t),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read(out.join("dem/demand.csv")).unwrap()
    };
    let all = "s1,500,ML\non-up,1450,ML\non-down,1550,ML\ns2,2000,ML\noff-up,2250,ML\n\
               s3,2600,ML\ns4,2900,ML\nend,2990,ML\noff-off,2300,FR\n";
    assert!(table(all) == std::fs::read(d.join("dem/demand.csv")).unwrap());
    assert!(table(&all.replace("s1,500,ML\n", "")) != table(all));
}

#[test]
fn bad_parameters_files_name_the_key_and_value() {
    let d = scratch("errors");
    let field = d.join("field.csv");
    std::fs::write(
        &field,
        "station,time,flow_vph,speed_kmh,occupancy\ns1,07:00,1000,90,0.1\ns1,07:10,1000,90,0.1\n",
    )
    .unwrap();
    let cases = [
        (
            "budget = 8\nbogus = 2\n[params]\n\"human.buffer_s\" = { min = 0.0, max = 0.6 }\n",
            &["bogus", "unknown key"][..],
        ),
        (
            "budget = 8\n[params]\n\"human.buffer_s\" = { min = 0.6, max = 0.6 }\n",
            &[
                "params.\"human.buffer_s\"",
                "min = 0.6 is not below max = 0.6",
            ],
        ),
        (
            "budget = 0\n[params]\n\"human.buffer_s\" = { min = 0.0, max = 0.6 }\n",
            &["budget", "0 is not an integer in [1, 100000]"],
        ),
        (
            "budget = 8\n[params]\n\"run.penetration\" = { min = 0.0, max = 1.5 }\n",
            &["params.\"run.penetration\".max = 1.5", "[0, 1]"],
        ),
        (
            "budget = 8\n[params]\n\"human.no_such_key\" = { min = 0.0, max = 1 }\n",
            &["params.\"human.no_such_key\"", "no_such_key"],
        ),
    ];
    for (text, wanted) in cases {
        let p = d.join("p.toml");
        std::fs::write(&p, text).unwrap();
        let o = platoonsim(&[
            "-q",
            "calibrate",
            &scenario(),
            "--field",
            s(&field),
            "--params",
            s(&p),
            "--out",
            s(&d.join("out")),
        ]);
        assert_eq!(o.status.code(), Some(1), "{text}");
        let e = stderr(&o);
        for w in wanted {
            assert!(e.contains(w), "{text}: wanted {w:?} in {e}");
        }
    }
}

//! The readers on the repository's PeMS SR-99 data (data/pems-sr99, 2014-09-18).

use std::path::PathBuf;

use platoonsim_field::{aggregate, load, pems, place, StationKind};

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/pems-sr99")
        .join(name)
}

fn station_5min() -> PathBuf {
    data("d03_text_station_5min_2014_09_18.txt.gz")
}

fn meta() -> Vec<platoonsim_field::StationMeta> {
    pems::read_meta(&data("d03_text_meta_2014_09_18.txt")).unwrap()
}

#[test]
fn station_5min_reads_every_line_with_exact_values() {
    let day = pems::read_day(&station_5min()).unwrap();
    assert_eq!(day.date.unwrap().to_string(), "2014-09-18");
    // 20448 lines = 71 stations × 288 intervals, every one with a flow.
    assert_eq!(day.obs.len(), 20448);
    // 09/18/2014 00:00:00,317652,3,99,N,ML,,,,74,0.0421,64.1
    let o = &day.obs[0];
    assert_eq!(o.station, "317652");
    assert_eq!((o.start_s, o.interval_s), (0, 300));
    assert_eq!(o.flow_vph, 888.0);
    assert_eq!(o.speed_kmh, Some(64.1 * 1.609344));
    assert_eq!(o.occupancy, Some(0.0421));
    // Rows with `nan` occupancy and an empty speed read as None (1288 and 8048 of them).
    assert_eq!(
        day.obs.iter().filter(|o| o.occupancy.is_none()).count(),
        1288
    );
    assert_eq!(
        day.obs.iter().filter(|o| o.speed_kmh.is_none()).count(),
        8048
    );
    // load sniffs the gzip file as PeMS and gives the same rows.
    assert_eq!(load::load(&[station_5min()]).unwrap(), day.obs);
}

#[test]
fn meta_reads_every_station() {
    let meta = meta();
    assert_eq!(meta.len(), 109);
    let count = |k: StationKind| meta.iter().filter(|m| m.kind == k).count();
    assert_eq!(count(StationKind::Mainline), 46);
    assert_eq!(count(StationKind::OnRamp), 20);
    assert_eq!(count(StationKind::OffRamp), 12);
    assert_eq!(count(StationKind::Hov), 29);
    assert_eq!(count(StationKind::FreewayConnector), 2);
    let elk = meta.iter().find(|m| m.id == "313190").unwrap();
    assert_eq!(elk.abs_pm, 287.295);
    assert_eq!(elk.kind, StationKind::Mainline);
    assert_eq!(elk.lanes, 2);
    assert_eq!(elk.name, "Elk Grove Blvd");
    assert_eq!((elk.freeway.as_str(), elk.direction.as_str()), ("99", "N"));
}

#[test]
fn sr99_corridor_mainline_stations_by_postmile() {
    let placed = place::by_postmile(&meta(), 287.230, -500.0, 17160.0);
    let mainline: Vec<&str> = placed
        .iter()
        .filter(|p| p.kind == StationKind::Mainline)
        .map(|p| p.station.as_str())
        .collect();
    // From the metadata: Type ML, (Abs_PM - 287.230) × 1609.344 in [-500, 17160], by postmile.
    let expected = [
        "319481", "313190", "314697", "313166", "313172", "313178", "317960", "317948", "314625",
        "312648", "312651", "312233", "312382", "312386", "312388", "317910", "312421", "312422",
        "312425", "312513", "312514", "312520", "312523", "312525", "312527", "317896", "312562",
        "318566",
    ];
    assert_eq!(mainline, expected);
    let elk = placed.iter().find(|p| p.station == "313190").unwrap();
    assert!((elk.x_m - 0.065 * 1609.344).abs() < 1e-9, "{}", elk.x_m);
    assert!(placed.windows(2).all(|w| w[0].x_m <= w[1].x_m));
    assert!(placed.iter().all(|p| (-500.0..=17160.0).contains(&p.x_m)));
}

#[test]
fn selection_reports_the_station_without_metadata_and_the_held_out_ones() {
    let obs = pems::read_station_5min(&station_5min()).unwrap();
    let all = place::by_postmile(&meta(), 287.230, f64::NEG_INFINITY, f64::INFINITY);
    let sel = place::select(&obs, &all);
    // data/pems-sr99/README.md: 315825 is in the 5-minute file, not in the metadata.
    assert_eq!(sel.ignored_stations, ["315825"]);
    assert_eq!(sel.obs.len(), 20448 - 288);
    // 109 listed stations, 70 of them with rows.
    assert_eq!(sel.without_data.len(), 39);
    assert!(sel.without_data.contains(&"312425".to_string()));
    assert!(place::require(&all, &["313190"]).is_ok());
    assert!(place::require(&all, &["315825"]).is_err());
}

#[test]
fn a_complete_day_aggregates_to_15_minutes_with_nothing_missing() {
    let obs = pems::read_station_5min(&station_5min()).unwrap();
    assert!(aggregate::missing(&obs, 0, 86_400, 300).is_empty());
    let q = aggregate::to_interval(&obs, 900);
    assert_eq!(q.len(), 71 * 96);
    // 313190 at 07:00, 07:05, 07:10: 61, 61, 39 vehicles at 15.5, 10.1, 8.2 mph.
    let o = q
        .iter()
        .find(|o| o.station == "313190" && o.start_s == 7 * 3600)
        .unwrap();
    assert_eq!(o.flow_vph, (61.0 + 61.0 + 39.0) * 12.0 / 3.0);
    let mph = (61.0 * 15.5 + 61.0 * 10.1 + 39.0 * 8.2) / 161.0;
    assert!((o.speed_kmh.unwrap() - mph * 1.609344).abs() < 1e-9);
    assert!((o.occupancy.unwrap() - (0.2365 + 0.3347 + 0.1812) / 3.0).abs() < 1e-12);
}

//! `platoonsim time-space`: a time-space diagram of one lane from a trajectories.csv. This
//! module reads the file; the drawing is `platoonsim_plot::time_space`.

use crate::args::TimeSpaceArgs;
use anyhow::{bail, Context, Result};
use platoonsim_plot::{TimeSpace, Track, TrackSample};
use platoonsim_rundir::trajectory::read_samples;
use std::collections::{BTreeSet, HashMap};
use std::io::Read;
use std::path::Path;

pub fn time_space(args: &TimeSpaceArgs) -> Result<()> {
    let lane = args.lane()?;
    use platoonsim_scenario::bounded;
    let file = bounded::open_records(
        &args.csv,
        bounded::MAX_RECORD_FILE_BYTES,
        bounded::MAX_RECORD_LINE_BYTES,
    )
    .with_context(|| format!("cannot read {}", args.csv.display()))?;
    let tracks = read_tracks(file, &args.csv, lane)?;
    let title = format!("Time-space diagram, lane {lane} (lane 1 = rightmost)");
    let ts = TimeSpace {
        title,
        lane,
        tracks,
    };
    let stem = args.stem(lane);
    let files = platoonsim_plot::time_space(&ts, &stem)?;
    for f in files {
        outln!("{}", f.display())?;
    }
    Ok(())
}

/// The vehicles of `lane` from a trajectories.csv: per vehicle, its samples in the lane and,
/// where it left the lane, the first sample in another lane (which breaks the line; the other
/// samples elsewhere are not kept, so memory follows the lane drawn). Errors name the file,
/// and for a bad row the line and the column.
pub fn read_tracks<R: Read>(input: R, path: &Path, lane: u32) -> Result<Vec<Track>> {
    let name = path.display().to_string();
    let mut tracks: Vec<Track> = vec![];
    // Vehicle id -> (index in `tracks`, whether its last sample was in the lane).
    let mut index: HashMap<u64, (usize, bool)> = HashMap::new();
    let mut lanes = BTreeSet::new();
    let mut in_lane = 0usize;
    // The one reader of the file (`platoonsim_rundir::trajectory`, shared with the viewer):
    // it checks the header and every cell; files of the first format (before `platoon_pos`
    // and `regime`) read too.
    read_samples(input, &name, |s| {
        let row_lane = s.lane;
        lanes.insert(row_lane);
        let here = row_lane == lane;
        let entry = index.get(&s.id).copied();
        // Samples elsewhere are kept only to break a line that was in the lane.
        let keep = here || entry.is_some_and(|(_, was_here)| was_here);
        if keep {
            let i = match entry {
                Some((i, _)) => i,
                None => {
                    tracks.push(Track {
                        cav: s.is_cav(),
                        samples: vec![],
                    });
                    tracks.len() - 1
                }
            };
            tracks[i].samples.push(TrackSample {
                t_s: s.t_s,
                lane: row_lane,
                x_m: s.x_m,
                v_mps: s.v_mps,
            });
            index.insert(s.id, (i, here));
        }
        in_lane += usize::from(here);
        Ok(())
    })
    .map_err(anyhow::Error::msg)?;
    if in_lane == 0 {
        if lanes.is_empty() {
            bail!("{name} has no samples (only the header): nothing to draw");
        }
        let list = lanes
            .iter()
            .map(u32::to_string)
            .collect::<Vec<_>>()
            .join(", ");
        bail!(
            "{name} has no sample in lane {lane}: nothing to draw (its samples are in lanes \
             {list}; choose one with --lane)"
        );
    }
    Ok(tracks)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str, lane: u32) -> Result<Vec<Track>> {
        read_tracks(text.as_bytes(), Path::new("t.csv"), lane)
    }

    const HEAD: &str = "t_s,id,kind,lane,x_m,v_mps,a_mps2,mode\n";

    #[test]
    fn keeps_the_lane_and_the_first_sample_elsewhere() {
        let text = format!(
            "{HEAD}0,7,cav,1,0,20,0,cf\n0,8,human,2,5,10,0,cf\n1,7,cav,2,20,20,0,blc\n\
             2,7,cav,2,40,20,0,cf\n3,7,cav,1,60,20,0,ycf-auto\n"
        );
        let tracks = read(&text, 1).unwrap();
        assert_eq!(tracks.len(), 1, "vehicle 8 never is in lane 1");
        assert!(tracks[0].cav);
        let lanes: Vec<u32> = tracks[0].samples.iter().map(|s| s.lane).collect();
        assert_eq!(lanes, [1, 2, 1]);
        // In lane 2, vehicle 8 comes first (vehicle 7's first sample is elsewhere).
        let tracks = read(&text, 2).unwrap();
        assert_eq!(tracks.len(), 2);
        assert!(!tracks[0].cav && tracks[1].cav);
        assert_eq!(tracks[1].samples.len(), 3, "two in lane 2, then the break");
    }

    #[test]
    fn refusals_name_the_problem() {
        let err = |text: &str, lane| format!("{:#}", read(text, lane).unwrap_err());
        let e = err("a,b,c\n1,2,3\n", 1);
        assert!(
            e.contains("not a trajectories.csv") && e.contains("'a,b,c'"),
            "{e}"
        );
        let e = err(
            &format!("{HEAD}0,7,cav,1,0,20,0,cf\n1,7,cav,1,zz,20,0,cf\n"),
            1,
        );
        assert!(
            e.contains("line 3, column x_m: 'zz' is not a finite number"),
            "{e}"
        );
        let e = err(&format!("{HEAD}0,7,truck,1,0,20,0,cf\n"), 1);
        assert!(e.contains("line 2, column kind"), "{e}");
        let e = err(&format!("{HEAD}0,7,cav,0,0,20,0,cf\n"), 1);
        assert!(e.contains("line 2, column lane"), "{e}");
        let e = err(&format!("{HEAD}0,7,cav,1,0,NaN,0,cf\n"), 1);
        assert!(e.contains("line 2, column v_mps"), "{e}");
        let e = err(&format!("{HEAD}0,7,cav,1,0\n"), 1);
        assert!(e.contains("line 2: 5 fields, expected 8"), "{e}");
        let e = err(
            &format!("{HEAD}0,7,cav,1,0,20,0,cf\n0,8,cav,3,0,20,0,cf\n"),
            2,
        );
        assert!(
            e.contains("no sample in lane 2") && e.contains("lanes 1, 3"),
            "{e}"
        );
        let e = err(HEAD, 1);
        assert!(e.contains("no samples"), "{e}");
        let e = err("", 1);
        assert!(e.contains("not a trajectories.csv"), "{e}");
    }
}

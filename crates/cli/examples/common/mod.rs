//! Shared by the diagnostic examples: a scenario by name or file, with `--set` overrides.
use platoonsim_scenario::Overrides;
use platoonsim_sim::Simulation;

/// The simulation of scenario `name` (built-in or file) with each of `sets` as a `--set`.
pub fn simulation(name: &str, sets: &[String]) -> Simulation {
    let ov = Overrides {
        set: sets.to_vec(),
        ..Overrides::default()
    };
    let cfg = platoonsim_scenario::load_with(name, &ov).expect("scenario");
    Simulation::new(cfg).expect("sim")
}

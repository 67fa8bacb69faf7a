//! Steering a run between steps, from the library: commands to single vehicles (module
//! `command`: what they do, applied in the decide phase by `decide/commands.rs`) and the V2V
//! packet loss (spec 9.3). Methods of [`Simulation`]; no phase imports this module.

use crate::automation::Beacons;
use crate::command::{Active, Command, MAX_COMMAND_ACCEL_MPS2};
use crate::error::SimError;
use crate::sim::Simulation;
use platoonsim_model::lanechange::Side;

impl Simulation {
    /// Command vehicle `id` (on the road now) from the next step on (module `command`).
    pub fn command(&mut self, id: u64, command: Command) -> Result<(), SimError> {
        let Some(s) = self.traffic.slot_of(id) else {
            return Err(SimError::Command(format!(
                "vehicle {id} is not on the road"
            )));
        };
        let v = &self.traffic.vehicles[s as usize];
        let mut active = Active {
            id,
            command,
            left: 0,
            own_speed: v.driver.human.desired_speed,
        };
        match command {
            Command::Accelerate { accel_mps2, steps }
            | Command::AccelerateCapped { accel_mps2, steps }
            | Command::AccelerateSafe { accel_mps2, steps } => {
                if !(accel_mps2.is_finite() && accel_mps2.abs() <= MAX_COMMAND_ACCEL_MPS2) {
                    return Err(SimError::Command(format!(
                        "Accelerate.accel_mps2 = {accel_mps2}: must be finite, within \
                         ±{MAX_COMMAND_ACCEL_MPS2} m/s²"
                    )));
                }
                if steps == 0 {
                    return Err(SimError::Command(
                        "Accelerate.steps = 0: must be at least 1".into(),
                    ));
                }
                active.left = steps;
            }
            Command::DesiredSpeed { speed_mps } => {
                if !(speed_mps.is_finite() && (0.0..=100.0).contains(&speed_mps)) {
                    return Err(SimError::Command(format!(
                        "DesiredSpeed.speed_mps = {speed_mps}: must be in [0, 100] m/s"
                    )));
                }
                // A second DesiredSpeed keeps the driver's own speed of the first.
                if let Some(a) = self
                    .control
                    .commands
                    .iter()
                    .find(|a| a.id == id && matches!(a.command, Command::DesiredSpeed { .. }))
                {
                    active.own_speed = a.own_speed;
                }
                self.release_kind(id, |c| matches!(c, Command::DesiredSpeed { .. }));
                self.traffic.vehicles[s as usize].driver.human.desired_speed = speed_mps;
            }
            Command::ChangeLane { side } => {
                let to = match side {
                    Side::Left => v.lane + 1,
                    Side::Right => v.lane.wrapping_sub(1),
                };
                if !self.road.geom.can_enter(to, v.x) {
                    return Err(SimError::Command(format!(
                        "vehicle {id} cannot change {side:?} at x = {:.1} m: no lane it may \
                         enter there",
                        v.x + self.cfg.road.origin_m()
                    )));
                }
                active.left = u64::from(to);
            }
            Command::Release => {
                self.release_kind(id, |_| true);
                return Ok(());
            }
        }
        self.control.commands.push(active);
        Ok(())
    }

    /// The vehicles under command now (ids, in the order the commands were given).
    pub fn commanded(&self) -> impl Iterator<Item = u64> + '_ {
        self.control.commands.iter().map(|a| a.id)
    }

    /// End the commands of `id` that `which` selects (restoring a desired speed).
    fn release_kind(&mut self, id: u64, which: impl Fn(&Command) -> bool) {
        let slot = self.traffic.slot_of(id);
        let mut k = 0;
        while k < self.control.commands.len() {
            let a = &self.control.commands[k];
            if a.id == id && which(&a.command) {
                if let (Command::DesiredSpeed { .. }, Some(s)) = (a.command, slot) {
                    self.traffic.vehicles[s as usize].driver.human.desired_speed = a.own_speed;
                }
                self.control.commands.remove(k);
            } else {
                k += 1;
            }
        }
    }

    /// Set the probability that a CAV's V2V beacon reception fails, from the next step on
    /// (spec 9.3; `cav.packet_loss`), e.g. a V2V outage (1) and its end (0). Must be in
    /// [0, 1]. With the delay and the loss off until now the broadcast log starts here, every
    /// vehicle's row filled with its current speed.
    pub fn set_packet_loss(&mut self, p: f64) -> Result<(), crate::SimError> {
        if !(0.0..=1.0).contains(&p) {
            return Err(crate::SimError::Command(format!(
                "packet_loss = {p}: must be in [0, 1]"
            )));
        }
        self.cfg.cav.packet_loss = p;
        if p == 0.0 {
            // Every reception of the next step succeeds (`receive` draws nothing at p = 0).
            for v in &mut self.traffic.vehicles {
                v.cacc.beacon_age = 0;
            }
        }
        let auto = &mut self.traffic.auto;
        match &mut auto.beacons {
            Some(b) => b.loss = p,
            None if p > 0.0 => {
                let mut b = Beacons::new(self.cfg.seed, 0, p, &self.cfg);
                for lane in &self.traffic.lanes {
                    for &s in lane {
                        b.fill(s, self.traffic.vehicles[s as usize].v);
                    }
                }
                auto.beacons = Some(b);
            }
            None => {}
        }
        Ok(())
    }
}

//! CMA-ES (Hansen & Ostermeier 2001; Hansen, "The CMA Evolution Strategy: A Tutorial",
//! arXiv:1604.00772) from the `cmaes` crate, driven generation by generation as ask/tell.
//!
//! The crate evaluates each candidate through a callback; a calibration wants the whole
//! generation first (to run its λ × replications simulations as one parallel, shardable,
//! resumable batch). So the optimizer is **replayed**: to ask for generation g, a fresh
//! `CMAES` with the same options and seed is stepped through generations 0..g with the
//! objective values already known (returned to its callback in the order it asks for them),
//! then stepped once more with placeholder values, and the points its callback saw in that
//! last step are generation g. The crate's state after a generation depends only on its seed
//! and the values it was told, so the replay is exact, in any process, at any thread count.
//! A replay costs g small updates of an n × n matrix: nothing next to one simulation.
//!
//! | option | value |
//! |---|---|
//! | initial mean | the start point, normalized ([`super::space`]) |
//! | initial step size σ₀ | `sigma` (default 0.3 of each key's range) |
//! | population λ | `population` (default 4 + ⌊3 ln n⌋) |
//! | seed | `seed` |
//! | termination | the budget (whole generations), else the crate's defaults (TolFun 1e-12, TolFunHist 1e-12, TolXUp 1e8, condition 1e14, stagnation, no effect) |

use cmaes::{CMAESOptions, DVector};
use std::cell::{Cell, RefCell};
use std::rc::Rc;

/// How the optimizer is set up.
#[derive(Clone, Debug, PartialEq)]
pub struct Setup {
    pub start: Vec<f64>,
    pub sigma: f64,
    pub population: usize,
    pub seed: u64,
}

/// What the optimizer asks next.
#[derive(Clone, Debug, PartialEq)]
pub enum Ask {
    /// The points of the next generation (λ points of ℝⁿ, in the crate's order).
    Points(Vec<Vec<f64>>),
    /// It stopped after the last told generation, for these reasons.
    Stopped(String),
}

/// The next generation, given the objective values of the generations before it (each
/// `population` values, in the order of the points that were asked).
pub fn ask(setup: &Setup, told: &[Vec<f64>]) -> Result<Ask, String> {
    let values: Vec<f64> = told.concat();
    let calls = Rc::new(Cell::new(0usize));
    let seen: Rc<RefCell<Vec<Vec<f64>>>> = Rc::default();
    let objective = {
        let (calls, seen) = (calls.clone(), seen.clone());
        move |x: &DVector<f64>| {
            let i = calls.get();
            calls.set(i + 1);
            seen.borrow_mut().push(x.iter().copied().collect());
            // Placeholder for the generation being asked: any finite value.
            values.get(i).copied().unwrap_or(0.0)
        }
    };
    let mut cma = CMAESOptions::new(setup.start.clone(), setup.sigma)
        .population_size(setup.population)
        .seed(setup.seed)
        .build(objective)
        .map_err(|e| format!("invalid CMA-ES options: {e:?}"))?;
    for g in told {
        if g.len() != setup.population {
            return Err(format!(
                "a generation has {} values, not population = {}",
                g.len(),
                setup.population
            ));
        }
        if let Some(stop) = cma.next() {
            return Ok(Ask::Stopped(format!("{:?}", stop.reasons)));
        }
    }
    let _ = cma.next();
    let seen = seen.borrow();
    Ok(Ask::Points(seen[seen.len() - setup.population..].to_vec()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sphere(x: &[f64]) -> f64 {
        x.iter().map(|v| (v - 0.3) * (v - 0.3)).sum()
    }

    fn setup() -> Setup {
        Setup {
            start: vec![0.8, 0.1],
            sigma: 0.3,
            population: 6,
            seed: 7,
        }
    }

    #[test]
    fn replayed_ask_tell_equals_the_crate_run_directly() {
        // The crate run on its own, recording every point it evaluates...
        let direct: Rc<RefCell<Vec<Vec<f64>>>> = Rc::default();
        let d = direct.clone();
        let mut cma = CMAESOptions::new(vec![0.8, 0.1], 0.3)
            .population_size(6)
            .seed(7)
            .build(move |x: &DVector<f64>| {
                let p: Vec<f64> = x.iter().copied().collect();
                let v = sphere(&p);
                d.borrow_mut().push(p);
                v
            })
            .unwrap();
        for _ in 0..8 {
            assert!(cma.next().is_none());
        }
        // ... and the replayed ask/tell give the same points, bit for bit.
        let mut told = Vec::new();
        let mut asked = Vec::new();
        for _ in 0..8 {
            let Ask::Points(p) = ask(&setup(), &told).unwrap() else {
                panic!("stopped")
            };
            told.push(p.iter().map(|x| sphere(x)).collect());
            asked.extend(p);
        }
        assert_eq!(asked, *direct.borrow());
        // It converges toward the minimum at (0.3, 0.3).
        let best = told.concat().into_iter().fold(f64::INFINITY, f64::min);
        assert!(best < 1e-3, "{best}");
    }

    #[test]
    fn a_wrong_generation_size_is_an_error() {
        assert!(ask(&setup(), &[vec![1.0; 5]])
            .unwrap_err()
            .contains("5 values"));
    }

    #[test]
    fn a_flat_objective_stops_it() {
        let mut told = Vec::new();
        for _ in 0..50 {
            match ask(&setup(), &told).unwrap() {
                Ask::Points(_) => told.push(vec![1.0; 6]),
                Ask::Stopped(why) => {
                    assert!(why.contains("TolFun"), "{why}");
                    return;
                }
            }
        }
        panic!("never stopped on a flat objective");
    }
}

//! Python values to and from the engine's types: overrides, events, vehicle columns.

use numpy::PyArray1;
use platoonsim_sim::events::Departure;
use platoonsim_sim::snapshot::VehicleColumns;
use platoonsim_sim::{Event, LaneChangeReason, Side};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// A Python value as a scenario value (what `--set KEY=VALUE` reads), or a `TypeError`
/// naming the key.
pub fn toml_value(key: &str, v: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    if v.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return v.extract::<i64>().map(toml::Value::Integer).map_err(|_| {
            PyTypeError::new_err(format!(
                "overrides[{key:?}]: the integer {v} does not fit a scenario value (64-bit)"
            ))
        });
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(v.extract()?));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(v.extract()?));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let items = v
            .try_iter()?
            .map(|item| toml_value(key, &item?))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(toml::Value::Array(items));
    }
    // numpy scalars and other numbers: as a float if they say they are one.
    if let Ok(f) = v.extract::<f64>() {
        if v.hasattr("__index__")? {
            if let Ok(i) = v.extract::<i64>() {
                return Ok(toml::Value::Integer(i));
            }
        }
        return Ok(toml::Value::Float(f));
    }
    let ty = v.get_type().name()?.to_string();
    Err(PyTypeError::new_err(format!(
        "overrides[{key:?}]: a value of type {ty} is not a scenario value (use bool, int, \
         float, str, or a list of them)"
    )))
}

/// The `--set` arguments of an overrides dict, in its order.
pub fn set_args(overrides: &Bound<'_, PyDict>) -> PyResult<Vec<String>> {
    let mut out = Vec::with_capacity(overrides.len());
    for (k, v) in overrides.iter() {
        let key: String = k.extract().map_err(|_| {
            PyTypeError::new_err(format!(
                "overrides: the key {} is not a string (keys are dotted scenario keys such as \
                 \"run.penetration\")",
                k.repr().map(|r| r.to_string()).unwrap_or_default()
            ))
        })?;
        if key.contains('=') {
            return Err(PyTypeError::new_err(format!(
                "overrides: the key {key:?} contains '=' (keys are dotted scenario keys such \
                 as \"run.penetration\")"
            )));
        }
        let value = toml_value(&key, &v)?;
        out.push(format!("{key}={value}"));
    }
    Ok(out)
}

fn i64s(ids: impl Iterator<Item = u64>) -> Vec<i64> {
    ids.map(|i| i as i64).collect()
}

/// The columns as a dict of numpy arrays (docs/python.md lists them).
pub fn columns_dict<'py>(py: Python<'py>, c: &VehicleColumns) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("id", PyArray1::from_vec(py, i64s(c.id.iter().copied())))?;
    d.set_item(
        "kind",
        PyArray1::from_vec(py, c.kind.iter().map(|&k| k as i8).collect()),
    )?;
    d.set_item(
        "lane",
        PyArray1::from_vec(py, c.lane.iter().map(|&l| l as i32).collect()),
    )?;
    d.set_item("x_m", PyArray1::from_slice(py, &c.x_m))?;
    d.set_item("v_mps", PyArray1::from_slice(py, &c.v_mps))?;
    d.set_item("a_mps2", PyArray1::from_slice(py, &c.a_mps2))?;
    d.set_item(
        "mode",
        PyArray1::from_vec(py, c.mode.iter().map(|&m| m as i8).collect()),
    )?;
    d.set_item("regime", PyArray1::from_slice(py, &c.regime))?;
    d.set_item(
        "platoon_id",
        PyArray1::from_vec(py, i64s(c.platoon_id.iter().copied())),
    )?;
    d.set_item(
        "platoon_pos",
        PyArray1::from_vec(py, c.platoon_pos.iter().map(|&p| p as i32).collect()),
    )?;
    d.set_item(
        "leader_id",
        PyArray1::from_vec(
            py,
            c.leader_id
                .iter()
                .map(|l| l.map_or(-1, |i| i as i64))
                .collect(),
        ),
    )?;
    d.set_item("length_m", PyArray1::from_slice(py, &c.length_m))?;
    Ok(d)
}

fn reason(r: LaneChangeReason) -> &'static str {
    r.as_str()
}

/// One event as a dict: `type`, `t_s`, and the fields of its kind (docs/python.md).
pub fn event_dict<'py>(py: Python<'py>, e: &Event) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("t_s", e.t_s())?;
    match e {
        Event::Entered {
            id,
            kind,
            entrance,
            lane,
            x_m,
            v_mps,
            ..
        } => {
            d.set_item("type", "entered")?;
            d.set_item("id", id)?;
            d.set_item("kind", kind.as_str())?;
            d.set_item("entrance", entrance)?;
            d.set_item("lane", lane)?;
            d.set_item("x_m", x_m)?;
            d.set_item("v_mps", v_mps)?;
        }
        Event::Exited {
            id,
            kind,
            how,
            x_m,
            v_mps,
            ..
        } => {
            d.set_item("type", "exited")?;
            d.set_item("id", id)?;
            d.set_item("kind", kind.as_str())?;
            let (how, ramp) = match how {
                Departure::OffRamp(r) => ("off-ramp", Some(*r)),
                Departure::RoadEnd => ("road-end", None),
                Departure::Collided => ("collided", None),
                Departure::OnRoad => ("on-road", None),
            };
            d.set_item("how", how)?;
            d.set_item("off_ramp", ramp)?;
            d.set_item("x_m", x_m)?;
            d.set_item("v_mps", v_mps)?;
        }
        Event::LaneChange {
            id,
            kind,
            from,
            to,
            x_m,
            reason: why,
            cooperative,
            ..
        } => {
            d.set_item("type", "lane_change")?;
            d.set_item("id", id)?;
            d.set_item("kind", kind.as_str())?;
            d.set_item("from_lane", from)?;
            d.set_item("to_lane", to)?;
            d.set_item("side", if to > from { "left" } else { "right" })?;
            d.set_item("x_m", x_m)?;
            d.set_item("reason", reason(*why))?;
            d.set_item("cooperative", cooperative)?;
        }
        Event::ModeChange {
            id,
            kind,
            from,
            to,
            regime_from,
            regime_to,
            ..
        } => {
            d.set_item("type", "mode_change")?;
            d.set_item("id", id)?;
            d.set_item("kind", kind.as_str())?;
            d.set_item("from_mode", from.as_str())?;
            d.set_item("to_mode", to.as_str())?;
            d.set_item("from_regime", regime_from.map(|r| r.as_str()))?;
            d.set_item("to_regime", regime_to.map(|r| r.as_str()))?;
        }
        Event::HardBraking {
            id,
            kind,
            decel_mps2,
            ..
        } => {
            d.set_item("type", "hard_braking")?;
            d.set_item("id", id)?;
            d.set_item("kind", kind.as_str())?;
            d.set_item("decel_mps2", decel_mps2)?;
        }
        Event::Collision(c) => {
            d.set_item("type", "collision")?;
            d.set_item("id", c.vehicle)?;
            d.set_item("kind", c.vehicle_kind)?;
            d.set_item("collision", c.kind.as_str())?;
            d.set_item("lane", c.lane)?;
            d.set_item("x_m", c.x_m)?;
            d.set_item("v_mps", c.v_mps)?;
            d.set_item("other", c.other)?;
            d.set_item("other_kind", c.other_kind)?;
            d.set_item("overlap_m", c.overlap_m)?;
        }
    }
    Ok(d)
}

/// `"left"` / `"right"` as a side, or a `ValueError`.
pub fn parse_side(s: &str) -> Option<Side> {
    match s {
        "left" => Some(Side::Left),
        "right" => Some(Side::Right),
        _ => None,
    }
}

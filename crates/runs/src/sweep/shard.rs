//! Which share of a sweep's runs this process computes: `--shard I/N` (1-based), or the
//! array index of the scheduler that started it. Run `r` (in table order, cell by cell and
//! seed by seed) belongs to shard `r mod N + 1`: a deterministic split that spreads every
//! cell over the shards.
//!
//! | scheduler | index | count |
//! |---|---|---|
//! | Slurm job array | `SLURM_ARRAY_TASK_ID` − `SLURM_ARRAY_TASK_MIN` + 1 | `SLURM_ARRAY_TASK_COUNT`, else `MAX` − `MIN` + 1 |
//! | Kubernetes Indexed Job | `JOB_COMPLETION_INDEX` + 1 (it counts from 0) | `--shards N` |
//! | HyperQueue tasks (`hq submit --array 0-(N-1)`, or N tasks of one job from its Python API) | `HQ_TASK_ID` + 1 (task ids from 0) | `--shards N` |

use std::fmt;

/// A shard that cannot be read from the command line or a scheduler's environment. The
/// messages name the flag or variable, its value and what is allowed.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ShardError {
    #[error(
        "invalid --shard '{0}': expected I/N with 1 <= I <= N (e.g. 2/8: the second of eight \
         shares)"
    )]
    Syntax(String),
    #[error("{name}={value:?} is not an integer")]
    NotInteger { name: &'static str, value: String },
    #[error("{source_var}: shard {index} of {count} does not exist (a shard is 1..=N, N >= 1)")]
    NoSuchShard {
        source_var: String,
        index: i64,
        count: i64,
    },
    #[error(
        "SLURM_ARRAY_TASK_ID is set but neither SLURM_ARRAY_TASK_COUNT nor \
         SLURM_ARRAY_TASK_MIN/MAX is: give the shard count with --shards N"
    )]
    SlurmCountMissing,
    #[error("{variable} is set ({scheduler}): give the shard count, {what}, with --shards N")]
    CountMissing {
        variable: &'static str,
        scheduler: &'static str,
        what: &'static str,
    },
}

/// Shard `index` of `count`, 1-based.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl Shard {
    /// `I/N` as on the command line.
    pub fn parse(text: &str) -> Result<Shard, ShardError> {
        let bad = || ShardError::Syntax(text.to_string());
        let (i, n) = text.split_once('/').ok_or_else(bad)?;
        let index: usize = i.trim().parse().map_err(|_| bad())?;
        let count: usize = n.trim().parse().map_err(|_| bad())?;
        Shard::new(index, count).ok_or_else(bad)
    }

    pub fn new(index: usize, count: usize) -> Option<Shard> {
        (count >= 1 && (1..=count).contains(&index)).then_some(Shard { index, count })
    }

    /// Whether run number `r` (0-based, table order) is this shard's.
    pub fn owns(&self, r: usize) -> bool {
        r % self.count + 1 == self.index
    }

    /// The shard named by a scheduler's environment (`get` reads a variable), if any;
    /// `count` is `--shards N`. Errors name the variable, its value and what is allowed.
    pub fn from_env(
        get: &dyn Fn(&str) -> Option<String>,
        count: Option<usize>,
    ) -> Result<Option<Shard>, ShardError> {
        let int = |name: &'static str| -> Result<Option<i64>, ShardError> {
            match get(name) {
                None => Ok(None),
                Some(v) if v.trim().is_empty() => Ok(None),
                Some(v) => v
                    .trim()
                    .parse::<i64>()
                    .map(Some)
                    .map_err(|_| ShardError::NotInteger {
                        name,
                        value: v.clone(),
                    }),
            }
        };
        let make = |index: i64, n: i64, what: String| -> Result<Option<Shard>, ShardError> {
            let shard = usize::try_from(index)
                .ok()
                .zip(usize::try_from(n).ok())
                .and_then(|(i, n)| Shard::new(i, n));
            shard.map(Some).ok_or(ShardError::NoSuchShard {
                source_var: what,
                index,
                count: n,
            })
        };
        if let Some(id) = int("SLURM_ARRAY_TASK_ID")? {
            let min = int("SLURM_ARRAY_TASK_MIN")?;
            let n = match (
                count,
                int("SLURM_ARRAY_TASK_COUNT")?,
                min,
                int("SLURM_ARRAY_TASK_MAX")?,
            ) {
                (Some(n), ..) => n as i64,
                (None, Some(c), ..) => c,
                (None, None, Some(lo), Some(hi)) => hi - lo + 1,
                _ => return Err(ShardError::SlurmCountMissing),
            };
            let index = id - min.unwrap_or(1) + 1;
            return make(index, n, format!("SLURM_ARRAY_TASK_ID={id}"));
        }
        if let Some(i) = int("JOB_COMPLETION_INDEX")? {
            let n = count.ok_or(ShardError::CountMissing {
                variable: "JOB_COMPLETION_INDEX",
                scheduler: "a Kubernetes Indexed Job",
                what: "the Job's completions",
            })?;
            return make(i + 1, n as i64, format!("JOB_COMPLETION_INDEX={i}"));
        }
        if let Some(i) = int("HQ_TASK_ID")? {
            let n = count.ok_or(ShardError::CountMissing {
                variable: "HQ_TASK_ID",
                scheduler: "a HyperQueue task",
                what: "the size of the array 0-(N-1)",
            })?;
            return make(i + 1, n as i64, format!("HQ_TASK_ID={i}"));
        }
        Ok(None)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env<'a>(vars: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        move |k| {
            vars.iter()
                .find(|(n, _)| *n == k)
                .map(|(_, v)| v.to_string())
        }
    }

    #[test]
    fn shards_partition_the_runs() {
        let shards: Vec<Shard> = (1..=3).map(|i| Shard::new(i, 3).unwrap()).collect();
        for r in 0..20 {
            assert_eq!(shards.iter().filter(|s| s.owns(r)).count(), 1);
        }
        assert_eq!(Shard::parse("2/3"), Ok(Shard { index: 2, count: 3 }));
        for bad in ["0/3", "4/3", "1/0", "x/2", "2", "-1/2"] {
            assert!(
                Shard::parse(bad).unwrap_err().to_string().contains(bad),
                "{bad}"
            );
        }
    }

    #[test]
    fn scheduler_variables() {
        let s = |vars: &[(&str, &str)], n| Shard::from_env(&env(vars), n);
        assert_eq!(s(&[], None), Ok(None));
        assert_eq!(
            s(
                &[
                    ("SLURM_ARRAY_TASK_ID", "0"),
                    ("SLURM_ARRAY_TASK_MIN", "0"),
                    ("SLURM_ARRAY_TASK_MAX", "3")
                ],
                None
            ),
            Ok(Shard::new(1, 4))
        );
        assert_eq!(
            s(
                &[
                    ("SLURM_ARRAY_TASK_ID", "3"),
                    ("SLURM_ARRAY_TASK_COUNT", "3"),
                    ("SLURM_ARRAY_TASK_MIN", "1")
                ],
                None
            ),
            Ok(Shard::new(3, 3))
        );
        assert_eq!(
            s(&[("JOB_COMPLETION_INDEX", "0")], Some(5)),
            Ok(Shard::new(1, 5))
        );
        assert_eq!(s(&[("HQ_TASK_ID", "3")], Some(4)), Ok(Shard::new(4, 4)));
        assert_eq!(s(&[("HQ_TASK_ID", "0")], Some(4)), Ok(Shard::new(1, 4)));
        assert!(s(&[("HQ_TASK_ID", "4")], None)
            .unwrap_err()
            .to_string()
            .contains("--shards"));
        assert!(s(&[("HQ_TASK_ID", "4")], Some(4))
            .unwrap_err()
            .to_string()
            .contains("HQ_TASK_ID=4"));
        assert!(s(&[("SLURM_ARRAY_TASK_ID", "x")], None)
            .unwrap_err()
            .to_string()
            .contains("SLURM_ARRAY_TASK_ID"));
        assert!(s(&[("JOB_COMPLETION_INDEX", "2")], None)
            .unwrap_err()
            .to_string()
            .contains("JOB_COMPLETION_INDEX"));
    }
}

//! Shards: one deterministic slice of a task list. Task k belongs to shard k mod N, so
//! every shard gets designs from the whole sample and the slices partition the list.
//!
//! `auto` reads the index from the environment of a job array: Slurm
//! (`SLURM_ARRAY_TASK_ID` minus `SLURM_ARRAY_TASK_MIN`, count `SLURM_ARRAY_TASK_COUNT`),
//! a Kubernetes indexed Job (`JOB_COMPLETION_INDEX`) or an AWS Batch array
//! (`AWS_BATCH_JOB_ARRAY_INDEX`); the count then comes from `--shards` or
//! `SLIPLOAD_SHARDS` when the scheduler does not give it.

use crate::base::error::OptError;

/// Shard `index` of `count` (index from 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// Index, 0 ≤ index < count.
    pub index: usize,
    /// Number of shards, ≥ 1.
    pub count: usize,
}

impl Shard {
    /// The whole task list.
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    /// Whether task `k` is in this shard.
    pub fn owns(&self, k: usize) -> bool {
        k % self.count == self.index
    }

    /// Parses `I/N` or `auto`; `shards` is `--shards`, `env` looks variables up.
    pub fn parse(
        spec: &str,
        shards: Option<usize>,
        env: &dyn Fn(&str) -> Option<String>,
    ) -> Result<Shard, OptError> {
        let num = |name: &str, v: &str| -> Result<usize, OptError> {
            v.trim().parse::<usize>().map_err(|_| {
                OptError::Shard(format!("{name} = {v:?} is not a non-negative integer"))
            })
        };
        let shard = if spec == "auto" {
            let count_from = |var: Option<&str>| -> Result<usize, OptError> {
                if let Some(n) = shards {
                    return Ok(n);
                }
                if let Some(var) = var
                    && let Some(v) = env(var)
                {
                    return num(var, &v);
                }
                match env("SLIPLOAD_SHARDS") {
                    Some(v) => num("SLIPLOAD_SHARDS", &v),
                    None => Err(OptError::Shard(
                        "the shard count is unknown: give --shards N or set SLIPLOAD_SHARDS".into(),
                    )),
                }
            };
            if let Some(id) = env("SLURM_ARRAY_TASK_ID") {
                let min = match env("SLURM_ARRAY_TASK_MIN") {
                    Some(m) => num("SLURM_ARRAY_TASK_MIN", &m)?,
                    None => 0,
                };
                let id = num("SLURM_ARRAY_TASK_ID", &id)?;
                Shard {
                    index: id.checked_sub(min).ok_or_else(|| {
                        OptError::Shard(format!(
                            "SLURM_ARRAY_TASK_ID {id} is below SLURM_ARRAY_TASK_MIN {min}"
                        ))
                    })?,
                    count: count_from(Some("SLURM_ARRAY_TASK_COUNT"))?,
                }
            } else if let Some(id) = env("JOB_COMPLETION_INDEX") {
                Shard {
                    index: num("JOB_COMPLETION_INDEX", &id)?,
                    count: count_from(None)?,
                }
            } else if let Some(id) = env("AWS_BATCH_JOB_ARRAY_INDEX") {
                Shard {
                    index: num("AWS_BATCH_JOB_ARRAY_INDEX", &id)?,
                    count: count_from(None)?,
                }
            } else {
                return Err(OptError::Shard(
                    "--shard auto: none of SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX, AWS_BATCH_JOB_ARRAY_INDEX is set".into(),
                ));
            }
        } else {
            let (i, n) = spec.split_once('/').ok_or_else(|| {
                OptError::Shard(format!("{spec:?}: expected I/N (e.g. 0/3) or auto"))
            })?;
            Shard {
                index: num("shard index", i)?,
                count: num("shard count", n)?,
            }
        };
        if shard.count == 0 || shard.index >= shard.count {
            return Err(OptError::Shard(format!(
                "index {} must be below the count {} (indices start at 0)",
                shard.index, shard.count
            )));
        }
        Ok(shard)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env_of<'a>(vars: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        move |k| {
            vars.iter()
                .find(|(n, _)| *n == k)
                .map(|(_, v)| v.to_string())
        }
    }

    #[test]
    fn explicit_and_scheduler_shards() {
        let none = env_of(&[]);
        assert_eq!(
            Shard::parse("1/3", None, &none).unwrap(),
            Shard { index: 1, count: 3 }
        );
        assert!(Shard::parse("3/3", None, &none).is_err());
        assert!(Shard::parse("a/3", None, &none).is_err());
        assert!(Shard::parse("auto", None, &none).is_err());
        let slurm = env_of(&[
            ("SLURM_ARRAY_TASK_ID", "5"),
            ("SLURM_ARRAY_TASK_MIN", "4"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ]);
        assert_eq!(
            Shard::parse("auto", None, &slurm).unwrap(),
            Shard { index: 1, count: 3 }
        );
        let k8s = env_of(&[("JOB_COMPLETION_INDEX", "2"), ("SLIPLOAD_SHARDS", "4")]);
        assert_eq!(
            Shard::parse("auto", None, &k8s).unwrap(),
            Shard { index: 2, count: 4 }
        );
        let aws = env_of(&[("AWS_BATCH_JOB_ARRAY_INDEX", "0")]);
        assert_eq!(
            Shard::parse("auto", Some(2), &aws).unwrap(),
            Shard { index: 0, count: 2 }
        );
        assert!(Shard::parse("auto", None, &aws).is_err());
    }

    #[test]
    fn shards_partition_the_tasks() {
        let n = 3;
        for k in 0..20 {
            let owners = (0..n)
                .filter(|&i| Shard { index: i, count: n }.owns(k))
                .count();
            assert_eq!(owners, 1);
        }
    }
}

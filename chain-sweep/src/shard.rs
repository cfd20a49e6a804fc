//! Splitting a sweep over independent processes: [`Shard`] `I/N` is every `N`-th point of the
//! grid, starting at `I`, so `N` processes (a SLURM job array, several machines) each compute one
//! shard into its own results file, and [`crate::merge_shards`] joins the files into the whole
//! diagram.
//!
//! Points are dealt out **interleaved**: point `(i, j)` has the grid-order position `i * ny + j`
//! and belongs to shard `position % N`. Neighbouring points cost alike (a slow corner of a phase
//! diagram is a block of the grid), so interleaving gives every shard its share of each region
//! and the shards finish at about the same time; contiguous blocks would leave one shard with the
//! whole slow corner.

use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use crate::grid::Grid;

/// Why a shard cannot be named. Every variant carries what was found.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ShardError {
    #[error("`{text}` is not a shard I/N (for example 0/8, the first of 8) or `slurm`: {reason}")]
    /// Not `I/N` or `slurm`.
    BadSpec {
        /// The shard as written.
        text: String,
        /// What is wrong with it.
        reason: String,
    },
    #[error("shard {index}/{count} does not exist: shards are numbered 0 to {}", count - 1)]
    /// A shard index past the last.
    OutOfRange {
        /// The shard index given.
        index: usize,
        /// The number of shards.
        count: usize,
    },
    #[error("a sweep cannot be split into 0 shards")]
    /// Zero shards.
    NoShards,
    /// `--shard slurm` outside a SLURM job array.
    #[error(
        "--shard slurm needs the environment variable {variable}, which SLURM sets only in a job \
         array (sbatch --array=0-N); outside one, give the shard as I/N"
    )]
    SlurmMissing {
        /// The environment variable.
        variable: &'static str,
    },
    #[error("the environment variable {variable} = `{value}` is not a whole number")]
    /// A SLURM variable that is not a whole number.
    SlurmNotANumber {
        /// The environment variable.
        variable: &'static str,
        /// Its value.
        value: String,
    },
    /// The array's task ids are not a contiguous range of `count` ids (a list such as
    /// `--array=1,5,9`, or a step that skips ids).
    #[error(
        "the SLURM array has task ids {min} to {max} in steps of {step} but SLURM_ARRAY_TASK_COUNT = {count}, \
         and this task's id is {id}: use a contiguous range such as --array=0-{}",
        count.saturating_sub(1)
    )]
    SlurmInconsistent {
        /// This task's id.
        id: usize,
        /// The smallest task id.
        min: usize,
        /// The largest task id.
        max: usize,
        /// The step between ids.
        step: usize,
        /// `SLURM_ARRAY_TASK_COUNT`.
        count: usize,
    },
    /// An array of one task whose id is not 0: most likely one task of an earlier array
    /// resubmitted on its own (`sbatch --array=3`), which SLURM runs as an array of one, so that
    /// `--shard slurm` would make it shard 0 of 1, the whole diagram.
    #[error(
        "this SLURM array has one task, id {id}: with --shard slurm it would be shard 0/1 and compute \
         the whole diagram into a file of its own. To redo task {id} of an array of N tasks, resubmit \
         the whole array (sbatch --array=0-<N-1>; finished shards find their points done and end at \
         once) or run that shard by hand with --shard {id}/N"
    )]
    SlurmLoneTask {
        /// This task's id.
        id: usize,
    },
}

/// Shard `index` of `count` (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Shard {
    index: usize,
    count: usize,
}

impl Shard {
    /// Shard `index` of `count` (`index < count`).
    pub fn new(index: usize, count: usize) -> Result<Self, ShardError> {
        match count {
            0 => Err(ShardError::NoShards),
            _ if index >= count => Err(ShardError::OutOfRange { index, count }),
            _ => Ok(Self { index, count }),
        }
    }

    /// `I` of `I/N`, from 0.
    pub fn index(self) -> usize {
        self.index
    }

    /// `N` of `I/N`.
    pub fn count(self) -> usize {
        self.count
    }

    /// Whether point `(i, j)` of `grid` belongs to this shard.
    pub fn contains(self, grid: &Grid, (i, j): (usize, usize)) -> bool {
        self.contains_position(i * grid.ys().len() + j)
    }

    /// Whether the point at grid-order position `i * ny + j` belongs to this shard.
    pub fn contains_position(self, position: usize) -> bool {
        position % self.count == self.index
    }

    /// The shard of this task of a SLURM job array, from `SLURM_ARRAY_TASK_ID` and
    /// `SLURM_ARRAY_TASK_COUNT` (and `SLURM_ARRAY_TASK_MIN`, `_STEP` if set, so that
    /// `--array=1-8` is shards 0/8 to 7/8).
    pub fn from_slurm_env() -> Result<Self, ShardError> {
        Self::from_slurm(|name| std::env::var(name).ok())
    }

    /// [`Shard::from_slurm_env`] with the variables looked up by `var`.
    pub fn from_slurm(var: impl Fn(&str) -> Option<String>) -> Result<Self, ShardError> {
        let number = |variable: &'static str, required: bool| -> Result<Option<usize>, ShardError> {
            match var(variable) {
                Some(value) => value
                    .trim()
                    .parse()
                    .map(Some)
                    .map_err(|_| ShardError::SlurmNotANumber { variable, value }),
                None if required => Err(ShardError::SlurmMissing { variable }),
                None => Ok(None),
            }
        };
        let id = number("SLURM_ARRAY_TASK_ID", true)?.unwrap_or_default();
        let count = number("SLURM_ARRAY_TASK_COUNT", true)?.unwrap_or_default();
        let min = number("SLURM_ARRAY_TASK_MIN", false)?.unwrap_or(0);
        let step = number("SLURM_ARRAY_TASK_STEP", false)?.unwrap_or(1).max(1);
        let max = number("SLURM_ARRAY_TASK_MAX", false)?.unwrap_or(min + count.saturating_sub(1) * step);
        let inconsistent = ShardError::SlurmInconsistent { id, min, max, step, count };
        if count == 0 {
            return Err(ShardError::NoShards);
        }
        if id < min || id > max || (id - min) % step != 0 || max < min || (max - min) / step + 1 != count {
            return Err(inconsistent);
        }
        if count == 1 && id != 0 {
            return Err(ShardError::SlurmLoneTask { id });
        }
        Self::new((id - min) / step, count)
    }

    /// The results file of this shard for the whole sweep's `path`: `pd.csv` becomes
    /// `pd.shard-3-of-8.csv` (the tag goes before the last extension, or at the end).
    pub fn file_name(self, path: &Path) -> PathBuf {
        let tag = format!("shard-{}-of-{}", self.index, self.count);
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let named = match name.rsplit_once('.') {
            Some((stem, ext)) if !stem.is_empty() => format!("{stem}.{tag}.{ext}"),
            _ => format!("{name}.{tag}"),
        };
        path.with_file_name(named)
    }
}

/// `I/N`.
impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// `I/N`, as on the command line (`--shard 3/8`).
impl FromStr for Shard {
    type Err = ShardError;

    fn from_str(text: &str) -> Result<Self, ShardError> {
        let bad = |reason: &str| ShardError::BadSpec { text: text.to_owned(), reason: reason.to_owned() };
        let (index, count) = text.split_once('/').ok_or_else(|| bad("expected I/N"))?;
        let index = index.trim().parse().map_err(|_| bad("I is not a whole number >= 0"))?;
        let count = count.trim().parse().map_err(|_| bad("N is not a whole number >= 1"))?;
        Self::new(index, count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    fn env(pairs: &[(&str, &str)]) -> impl Fn(&str) -> Option<String> {
        let map: HashMap<String, String> =
            pairs.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect();
        move |k| map.get(k).cloned()
    }

    #[test]
    fn shards_parse_and_partition_the_grid() {
        assert_eq!("3/8".parse::<Shard>(), Shard::new(3, 8));
        assert_eq!("8/8".parse::<Shard>(), Err(ShardError::OutOfRange { index: 8, count: 8 }));
        assert_eq!("0/0".parse::<Shard>(), Err(ShardError::NoShards));
        assert!(matches!("3-8".parse::<Shard>(), Err(ShardError::BadSpec { .. })));
        assert!(matches!("-1/8".parse::<Shard>(), Err(ShardError::BadSpec { .. })));
        let grid = Grid::new("0:1:5".parse().unwrap(), "0:1:7".parse().unwrap()).unwrap();
        for count in [1, 2, 3, 35, 40] {
            for ij in grid.indices() {
                let owners =
                    (0..count).filter(|&k| Shard::new(k, count).unwrap().contains(&grid, ij)).count();
                assert_eq!(owners, 1, "{ij:?} of {count}");
            }
        }
    }

    #[test]
    fn slurm_arrays_map_to_shards_or_say_why_not() {
        let ok = |pairs: &[(&str, &str)]| Shard::from_slurm(env(pairs));
        assert_eq!(ok(&[("SLURM_ARRAY_TASK_ID", "3"), ("SLURM_ARRAY_TASK_COUNT", "8")]), Shard::new(3, 8));
        let one_based = [
            ("SLURM_ARRAY_TASK_ID", "8"),
            ("SLURM_ARRAY_TASK_COUNT", "8"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_MAX", "8"),
        ];
        assert_eq!(ok(&one_based), Shard::new(7, 8));
        assert_eq!(
            ok(&[("SLURM_ARRAY_TASK_COUNT", "8")]),
            Err(ShardError::SlurmMissing { variable: "SLURM_ARRAY_TASK_ID" })
        );
        assert_eq!(
            ok(&[("SLURM_ARRAY_TASK_ID", "2")]),
            Err(ShardError::SlurmMissing { variable: "SLURM_ARRAY_TASK_COUNT" })
        );
        assert_eq!(
            ok(&[("SLURM_ARRAY_TASK_ID", "x"), ("SLURM_ARRAY_TASK_COUNT", "8")]),
            Err(ShardError::SlurmNotANumber { variable: "SLURM_ARRAY_TASK_ID", value: "x".into() })
        );
        // --array=1,5,9: three tasks, ids not contiguous.
        let list = [
            ("SLURM_ARRAY_TASK_ID", "5"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_MAX", "9"),
        ];
        let err = ok(&list).unwrap_err();
        assert!(
            matches!(err, ShardError::SlurmInconsistent { id: 5, min: 1, max: 9, step: 1, count: 3 }),
            "{err}"
        );
        assert!(err.to_string().contains("--array=0-2"), "{err}");
        assert!(matches!(
            ok(&[("SLURM_ARRAY_TASK_ID", "9"), ("SLURM_ARRAY_TASK_COUNT", "8")]),
            Err(ShardError::SlurmInconsistent { .. })
        ));
        // --array=0-14:2: eight tasks in steps of 2.
        let stepped = [
            ("SLURM_ARRAY_TASK_ID", "6"),
            ("SLURM_ARRAY_TASK_COUNT", "8"),
            ("SLURM_ARRAY_TASK_MIN", "0"),
            ("SLURM_ARRAY_TASK_MAX", "14"),
            ("SLURM_ARRAY_TASK_STEP", "2"),
        ];
        assert_eq!(ok(&stepped), Shard::new(3, 8));
        // sbatch --array=3, one task of an earlier array resubmitted on its own: SLURM makes it an
        // array of one (what slurm-wlm 22.05 sets), which must not become shard 0/1.
        let lone = [
            ("SLURM_ARRAY_TASK_ID", "3"),
            ("SLURM_ARRAY_TASK_COUNT", "1"),
            ("SLURM_ARRAY_TASK_MIN", "3"),
            ("SLURM_ARRAY_TASK_MAX", "3"),
            ("SLURM_ARRAY_TASK_STEP", "1"),
        ];
        let err = ok(&lone).unwrap_err();
        assert_eq!(err, ShardError::SlurmLoneTask { id: 3 });
        assert!(err.to_string().contains("--shard 3/N"), "{err}");
        assert!(!err.to_string().contains("  "), "one space between words: {err}");
        // --array=0: an array of one task is the whole diagram, as asked.
        assert_eq!(ok(&[("SLURM_ARRAY_TASK_ID", "0"), ("SLURM_ARRAY_TASK_COUNT", "1")]), Shard::new(0, 1));
    }

    #[test]
    fn shard_files_are_named_beside_the_whole_sweeps_file() {
        let s = Shard::new(3, 8).unwrap();
        assert_eq!(s.file_name(Path::new("out/pd.csv")), Path::new("out/pd.shard-3-of-8.csv"));
        assert_eq!(s.file_name(Path::new("pd")), Path::new("pd.shard-3-of-8"));
        assert_eq!(s.file_name(Path::new(".hidden")), Path::new(".hidden.shard-3-of-8"));
    }
}

//! Sharding of study grids over independent processes (Slurm job arrays, GNU parallel): shard `K/N`
//! takes the points `i` with `i mod N = K − 1` (round-robin, so each shard gets a similar mix of
//! cheap and expensive points). Every study CSV starts with a `point` column holding the global
//! point index and lists a point's rows together, so [`merge`] restores the unsharded file byte for
//! byte by ordering the points.

use crate::error::{Error, Result};
use std::path::Path;

/// Shard `index` (1-based) of `count`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// 1-based shard number `K`.
    pub index: usize,
    /// Number of shards `N`.
    pub count: usize,
}

impl Default for Shard {
    fn default() -> Self {
        Shard { index: 1, count: 1 }
    }
}

impl Shard {
    /// Parses `K/N` with `1 ≤ K ≤ N`.
    pub fn parse(text: &str) -> Result<Shard> {
        let bad = || Error::parameter("--shard", format!("`{text}`: expected K/N with 1 ≤ K ≤ N"));
        let (k, n) = text.split_once('/').ok_or_else(bad)?;
        let (index, count): (usize, usize) = (
            k.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if index == 0 || index > count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }

    /// True when global point `i` belongs to this shard.
    pub fn owns(&self, i: usize) -> bool {
        i % self.count == self.index - 1
    }

    /// The global indices of `total` points that belong to this shard.
    pub fn points(&self, total: usize) -> Vec<usize> {
        (0..total).filter(|&i| self.owns(i)).collect()
    }
}

/// Merges shard CSVs (same header, first column `point`) into the text of the unsharded file. Fails
/// when headers differ, a point appears in two files, or the points are not `0..n` without gaps
/// (a missing shard).
pub fn merge(files: &[&Path]) -> Result<String> {
    let mut header: Option<String> = None;
    let mut groups: Vec<(usize, String)> = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(file).map_err(|e| Error::io(file, e))?;
        let mut lines = text.lines();
        let h = lines
            .next()
            .ok_or_else(|| Error::data(file, Some(1), "empty file; expected a header"))?;
        if !h.starts_with("point,") {
            return Err(Error::data(
                file,
                Some(1),
                "expected a header starting with `point,`",
            ));
        }
        match &header {
            None => header = Some(h.to_string()),
            Some(first) if first != h => {
                return Err(Error::data(
                    file,
                    Some(1),
                    format!("header differs from the first file's: `{first}`"),
                ));
            }
            _ => {}
        }
        let mut current: Option<(usize, String)> = None;
        for (ln, line) in lines.enumerate() {
            let p: usize = line
                .split(',')
                .next()
                .and_then(|s| s.parse().ok())
                .ok_or_else(|| Error::data(file, Some(ln + 2), "expected a point index first"))?;
            match &mut current {
                Some((q, body)) if *q == p => {
                    body.push_str(line);
                    body.push('\n');
                }
                _ => {
                    groups.extend(current.take());
                    current = Some((p, format!("{line}\n")));
                }
            }
        }
        groups.extend(current);
    }
    groups.sort_by_key(|g| g.0);
    for (i, w) in groups.iter().enumerate() {
        if w.0 != i {
            return Err(Error::parameter(
                "merge",
                if w.0 < i {
                    format!(
                        "point {} appears twice (overlapping shards or repeated file)",
                        w.0
                    )
                } else {
                    format!("point {i} is missing (a shard file is missing)")
                },
            ));
        }
    }
    let mut out = header.ok_or_else(|| Error::parameter("merge", "no files given"))?;
    out.push('\n');
    for (_, body) in groups {
        out.push_str(&body);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_partition_the_points() {
        let shards: Vec<Shard> = (1..=3)
            .map(|k| Shard::parse(&format!("{k}/3")).unwrap())
            .collect();
        for i in 0..10 {
            assert_eq!(shards.iter().filter(|s| s.owns(i)).count(), 1);
        }
        assert!(Shard::parse("0/3").is_err());
        assert!(Shard::parse("4/3").is_err());
        assert!(Shard::parse("x").is_err());
    }

    #[test]
    fn merge_restores_order_and_detects_gaps_and_overlaps() {
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join("a.csv");
        let b = dir.path().join("b.csv");
        std::fs::write(&a, "point,v\n0,a\n0,b\n2,c\n").unwrap();
        std::fs::write(&b, "point,v\n1,d\n").unwrap();
        assert_eq!(merge(&[&a, &b]).unwrap(), "point,v\n0,a\n0,b\n1,d\n2,c\n");
        assert!(merge(&[&a]).is_err(), "point 1 missing");
        assert!(merge(&[&a, &b, &b]).is_err(), "point 1 twice");
    }
}
